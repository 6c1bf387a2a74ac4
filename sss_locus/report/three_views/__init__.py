"""The three-view chapter's figures and findings (with the survey-pass findings: follow-up).
"""
