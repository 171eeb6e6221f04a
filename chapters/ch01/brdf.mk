CHAPTERS += ch01
ch01_PROGS += ch01_brdf
ch01_brdf_SRC := chapters/ch01/ch01_brdf.c
ch01_brdf_MODULES := brdf sample frame vec rng error
ch01_brdf_LIBS := -lm
