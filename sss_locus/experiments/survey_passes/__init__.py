"""The survey-pass chapter and its second notebook, planning: two straight passes against
crossing angle, the planning bands, verdicts, the reduction on workers.
"""
