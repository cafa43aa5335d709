//! The section `patch`: ray `i` against bilinear patch `i` on each patch
//! workload (the quad workloads' parallelograms, twisted): rayhit's
//! `Patch` next to the textbook test, Reshetov's formulas ("Cool
//! Patches", Ray Tracing Gems ch. 8, 2019, as the test kit writes them
//! once: the quadratic in `u` from three triple products, then `v` and
//! `t` from two more, `t > 0`), and the `Quad` of the same corners (two
//! watertight triangles, for scale: not the same surface).

use rayhit::{Intersect, Patch, PreparedRay, Quad, Ray};
use rayhit_testkit::textbook::reshetov;
use rayhit_testkit::workloads::PatchWorkload;

use crate::harness::loops::{Orders, agree, pairwise, t_sum};
use crate::harness::{INF, Kernel, kernel};

/// A patch workload in every form its rows take.
pub struct PatchData {
    pub name: &'static str,
    pub order: Orders,
    pub rays: Vec<Ray>,
    pub prepared: Vec<PreparedRay>,
    pub patches: Vec<Patch>,
    pub quads: Vec<Quad>,
}

impl PatchData {
    pub fn new(w: PatchWorkload, shuffle: bool) -> Self {
        Self {
            name: w.name,
            order: Orders::new(w.rays.len(), shuffle),
            prepared: w.rays.iter().map(PreparedRay::new).collect(),
            quads: w
                .patches
                .iter()
                .map(|p| Quad::new(p.p00, p.p10, p.p11, p.p01))
                .collect(),
            rays: w.rays,
            patches: w.patches,
        }
    }
}

/// Pairwise patch kernels: ray `i` against patch `i`.
pub fn patch_kernels<'a>(d: &'a PatchData, out: &mut Vec<Kernel<'a>>) {
    let n = d.rays.len();
    let ours: Vec<bool> = (0..n)
        .map(|i| d.patches[i].hit(&d.rays[i], INF).is_some())
        .collect();
    let textbook_agree = agree(
        ours.iter().copied(),
        (0..n).map(|i| reshetov(&d.rays[i], &d.patches[i], 0.0, INF).is_some()),
    );
    let (w, sec) = (d.name, "patch");
    out.extend([
        kernel(
            sec,
            "rayhit Patch::hit",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.patches, |r, p| {
                t_sum(p.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "rayhit Patch::hit, PreparedRay",
            w,
            n,
            None,
            pairwise(&d.order, &d.prepared, &d.patches, |r, p| {
                t_sum(p.hit(r, INF).map(|h| h.t))
            }),
        ),
        kernel(
            sec,
            "textbook patch (Reshetov, t > 0)",
            w,
            n,
            Some(textbook_agree),
            pairwise(&d.order, &d.rays, &d.patches, |r, p| {
                t_sum(reshetov(r, p, 0.0, INF).map(|h| h.0))
            }),
        ),
        kernel(
            sec,
            "rayhit Quad::hit on the same corners",
            w,
            n,
            None,
            pairwise(&d.order, &d.rays, &d.quads, |r, q| {
                t_sum(q.hit(r, INF).map(|h| h.t))
            }),
        ),
    ]);
}
