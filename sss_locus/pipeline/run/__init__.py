"""Running notebooks: registry, runner, kernels, cache, atomic commits, preflight checks,
budgets, progress, a user's files as parameters.
"""
