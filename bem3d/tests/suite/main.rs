//! bem3d's integration tests in one binary (the workspace is linked once for them):
//! closed forms and a dense solve (`verification`), edge cases (`edges`), properties
//! over random inputs (`properties`), steady sliding (`sliding`), the transient
//! viscoelastic solver (`viscoelastic`) and the vector-width variants (`wide`).

mod common;
mod edges;
mod properties;
mod sliding;
mod verification;
mod viscoelastic;
mod wide;
