"""The noise chapter: the noise model and how range and navigation errors spread the loci.
"""
