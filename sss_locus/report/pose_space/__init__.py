"""The pose-space chapter's figures and findings.
"""
