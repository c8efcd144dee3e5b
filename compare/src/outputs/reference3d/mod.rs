//! 3D boundary-element references on the user's own height maps.

pub mod bem_contact;
