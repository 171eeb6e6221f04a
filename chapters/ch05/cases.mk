CHAPTERS += ch05
ch05_PROGS += ch05_cases
ch05_cases_SRC := chapters/ch05/ch05_cases.c
ch05_cases_MODULES := render tracer integrator light camera scene scenefile material brdf sample rng cobject shape sphere plane disk parallelogram triangle box cylinder cone quadric xform bbox ray frame vec colour image imgcompare converge netpbm tonemap fileio error
ch05_cases_LIBS := -lm
