//! The 3D inverse-rendering tasks.
