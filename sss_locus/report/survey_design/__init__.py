"""The survey-design chapter's figures and plan maps.
"""
