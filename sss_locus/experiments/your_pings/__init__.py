"""The your-pings chapter: a user's sightings and XTF files, per-feature results, the joint
adjustment of a user's sightings, the example survey.
"""
