"""Bolide analysis tools: snapshot and statistics readers, analytic solutions
(exact Riemann problem, Sedov-Taylor blast wave) and error norms.

Only numpy, scipy, h5py and matplotlib are used.  Modules:

  snapshot  load a Bolide (SWIFT-layout) HDF5 snapshot; read a statistics file
  riemann   exact Riemann solver for an ideal gas (Toro 2009, chapter 4)
  sedov     Sedov-Taylor point explosion in 3D (Sedov 1959; Kamm & Timmes 2007)
  l1        L1 error of particle values against an analytic profile
  common    small helpers shared by the command-line scripts
"""
