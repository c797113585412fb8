//! Raw bindings of gyro's C ABI (`capi/gyro.h`): `#[repr(C)]` structs and unions, opaque
//! handle types, the status and enum typedefs with their constants, and the `extern "C"`
//! functions. Everything is generated into [`ffi`] by `capi/api/gen_rust.py` from
//! `gyro_api.json`, the description the build makes of the header (with the C compiler's
//! sizes and offsets); `tests/layout.rs` checks rustc's layouts against those numbers.
//!
//! Use the `gyro` crate for a safe API. Names are the C names; the union `as` of
//! `gyro_shape_soa` is the field `r#as` of type `gyro_shape_soa_as`.
#![no_std]

pub mod ffi;
pub use ffi::*;
