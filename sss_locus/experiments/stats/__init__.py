"""Statistics shared by the chapters: replicate-batch intervals, row statistics, the Gaussian
norm quantile, and where the Monte Carlo chunks run (``scale``: this process or Dask).
"""
