"""Building the book: staging, indexes, the claims page, build areas, the PDF.
"""
