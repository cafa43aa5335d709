//! The batches (`AabbBatch`, `TriangleBatch`, `SphereBatch`) and the compressed wide BVH
//! node (`QuantizedChildren`): every lane bit for bit against the scalar
//! kernels, and the node against exact arithmetic. CI also runs these
//! (`cargo test --test suite batch::`) for aarch64 and x86-64-v3 and v4,
//! whose lanes differ.

mod face;
mod lanes;
mod node;
mod spheres;
