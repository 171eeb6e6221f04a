CHAPTERS += ch05
ch05_PROGS += ch05_cases
ch05_cases_SRC := chapters/ch05/ch05_cases.c
ch05_cases_MODULES := render tracer integrator light camera scene scenefile material brdf sample rng cobject shape sphere plane disk parallelogram triangle box cylinder cone quadric xform bbox ray frame vec colour image imgcompare converge netpbm tonemap fileio error
ch05_cases_LIBS := -lm
# what it must not link (make check-links): ch. 7's acceleration layer,
# structures and meshes; with link-time optimisation also the functions of
# parallelogram.c and xform.c that only the batched brute force calls;
# and none of the photon maps of ch. 8, the textures of ch. 10 or the
# media of ch. 11
ch05_cases_FORBID := volphoton accel batch grid primset mesh objmesh photon irrpart irrcache gradients subsample obj_ 'obj\.c\.' texture texpart noise_ solid_ mipmap bumpgen interp_ medium medpart volpath volsingle phase volgrid
ch05_cases_FORBID_LTO := parallelogram_batch_ parallelogram_intersect_prepared xform_culling_sphere xform_intersect_unculled
