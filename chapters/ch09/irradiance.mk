CHAPTERS += ch09
ch09_PROGS += ch09_irradiance
ch09_irradiance_SRC := chapters/ch09/ch09_irradiance.c
ch09_irradiance_MODULES := irrpart irrcache gradients render subsample tracer integrator light camera scene scenefile material brdf sample rng cobject shape sphere plane disk parallelogram triangle box cylinder cone quadric xform bbox ray frame vec colour image netpbm tonemap fileio error
ch09_irradiance_LIBS := -lm
# what it must not link (make check-links): ch. 7's acceleration layer and
# meshes, the other parts of Part II (photon maps, textures, media)
ch09_irradiance_FORBID := accel batch grid primset mesh objmesh photon photonmap texture texpart medium medpart volpath volsingle volgrid phase
