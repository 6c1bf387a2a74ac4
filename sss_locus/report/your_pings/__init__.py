"""The your-pings chapter's figures: maps, feature panels, waterfalls, the joint adjustment.
"""
