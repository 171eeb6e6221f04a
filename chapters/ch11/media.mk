CHAPTERS += ch11
ch11_PROGS += ch11_media
ch11_media_SRC := chapters/ch11/ch11_media.c
ch11_media_MODULES := medpart volpath volsingle medium phase volgrid interp render tracer integrator light camera scene scenefile material brdf sample rng cobject shape sphere plane disk parallelogram triangle box cylinder cone quadric xform bbox ray frame vec colour image netpbm tonemap fileio error
ch11_media_LIBS := -lm
# what it must not link (make check-links): ch. 7's acceleration layer and
# meshes, the other parts of Part II
ch11_media_FORBID := volphoton accel batch grid primset mesh objmesh photon photonmap irrcache irrpart texture texpart subsample
