//! Held against the literature: published reference results, each reproduced by MRD and
//! by the 3D solvers with its deviation and verdict (the data: `compare/data/`).

pub mod references;
