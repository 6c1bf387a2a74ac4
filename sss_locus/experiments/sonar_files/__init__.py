"""A user's recorded sonar files and the sightings picked on them: XTF bytes read strictly,
which end of a channel is near, layback, an XTF file's summary, sightings CSVs and XTF matches.
"""
