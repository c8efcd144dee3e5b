//! mrd's integration tests in one binary: properties over random inputs
//! (`properties`) and sliding on viscoelastic springs (`sliding`).

mod properties;
mod sliding;
