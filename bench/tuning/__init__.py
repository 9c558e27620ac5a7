"""The tuner's parts (bench/tune.py): budgets, knobs, one measured run, the frontier plot."""
