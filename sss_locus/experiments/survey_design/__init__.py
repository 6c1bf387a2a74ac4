"""The survey-design chapter: area polygons, lines and turns, routes, measured coverage,
objectives, plans, the Pareto front and the recommended plan, plans scored over seeds.
"""
