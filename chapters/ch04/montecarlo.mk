CHAPTERS += ch04
ch04_PROGS += ch04_montecarlo
ch04_montecarlo_SRC := chapters/ch04/ch04_montecarlo.c
ch04_montecarlo_MODULES := sample rng frame vec
ch04_montecarlo_LIBS := -lm
