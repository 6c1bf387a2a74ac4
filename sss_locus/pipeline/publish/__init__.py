"""Publishing: citable figures and tables, provenance, citation metadata, readability, mission
files.
"""
