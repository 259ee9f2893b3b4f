//! The atmosphere's test support: an independent double-precision reference of
//! the same physical model (Hillaire's Earth), and a probe that evaluates the real
//! WGSL on the GPU for chosen rays.
#![allow(dead_code)]

pub mod model;
pub mod orders;
pub mod probe;
pub mod reference;
pub mod transmittance;
