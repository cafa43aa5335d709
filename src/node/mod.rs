//! The BVH-node layer, above the shapes: what a traversal asks of a node
//! rather than of one shape.
//!
//! - `quantized.rs`: [`QuantizedChildren`], the children of a compressed
//!   wide BVH node read where the node keeps them.
//! - `with_simd.rs`: [`Simd`], [`SimdRay`], [`SimdWork`] and [`with_simd`],
//!   the batch and node kernels on an instruction set chosen once for a
//!   whole traversal.

mod quantized;
mod with_simd;

pub use quantized::{InPlace, QuantizedChildren};
pub use with_simd::{Simd, SimdRay, SimdWork, with_simd};
