CHAPTERS += ch08
ch08_PROGS += ch08_photons
ch08_photons_SRC := chapters/ch08/ch08_photons.c
ch08_photons_MODULES := photon photonmap photonsave render tracer integrator light camera scene scenefile material brdf sample rng cobject shape sphere plane disk parallelogram triangle box cylinder cone quadric xform bbox ray frame vec colour image netpbm tonemap fileio error
ch08_photons_LIBS := -lm
# what it must not link (make check-links): ch. 7's acceleration layer and
# meshes, the other parts of Part II
ch08_photons_FORBID := volphoton accel batch grid primset mesh objmesh irrcache irrpart medium texture texpart medpart volpath volsingle phase volgrid subsample
