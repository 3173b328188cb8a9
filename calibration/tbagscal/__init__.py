"""T-BAGS calibration against the Toyoura sand data, in modules with one job each (calibration/fit.py is
the command line): common, runs, evaluate, misfit, search, report, figure."""
