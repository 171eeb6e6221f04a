CHAPTERS += ch03
ch03_PROGS += ch03_estimator
ch03_estimator_SRC := chapters/ch03/ch03_estimator.c
ch03_estimator_MODULES := vec frame ray bbox cobject error rng sample brdf material sphere disk quadric shape camera
ch03_estimator_LIBS := -lm
