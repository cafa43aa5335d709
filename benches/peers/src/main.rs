//! rayhit's kernels next to `bvh` 0.13 and `parry3d` 0.31 on identical data
//! (the workloads of the test kit, `testkit/src/workloads.rs`), printed as one Markdown table,
//! followed by the speed ratios the crate aims for.
//!
//! ```sh
//! cargo run --release --manifest-path benches/peers/Cargo.toml
//! ```
//!
//! Timing: every kernel runs over its whole workload (4096 ray/shape tests
//! unless said otherwise) enough times to take at least 2 ms; the kernels
//! take turns, round after round, so that a change in machine load hits
//! them alike, and each one's time is its fastest round (the least
//! disturbed); a row whose pass is long enough that a round holds fewer
//! than four runs one untimed pass before each round, so that it is timed
//! with its own data in the caches, not the previous row's. Time is the thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`),
//! so that while other processes hold the core the clock stops; what they
//! do to shared caches still shows. `ns/test` is that time over the number
//! of ray/shape tests. The triangle pairs of the `random`, `aimed` and
//! `axis` workloads are visited in a fresh order on each pass (see
//! `harness::loops::Orders`).
//!
//! Agreement is the fraction of ray/shape pairs on which a peer's hit or
//! miss matches rayhit's answer to the same question: for `bvh`'s
//! triangle test, which drops back faces, that is rayhit's hits from the
//! front side; for every other kernel rayhit's two-sided answer.
//!
//! The parts: `harness` (the clock, the timing loop, the table) with
//! `harness::loops` (the rows' timed loops and checksums); `data` (the
//! workloads in every form the rows take); `peers` (the adapters to the
//! other crates); `floors` (the textbook and floor kernels written here);
//! `sections` (a file per section of the table, building its rows);
//! `targets` (the ratios printed after the table). This file reads the
//! arguments and builds the sections in the table's order.

use std::hint::black_box;
use std::time::Instant;

use rayhit_peers::cwbvh;
use rayhit_testkit::workloads::{box_workloads, triangle_workloads};

mod data;
mod floors;
mod harness;
mod peers;
mod sections;
mod targets;

use data::{BoxData, Groups, TriData};
use harness::{ROUNDS, time_all};
#[cfg(target_arch = "x86_64")]
use sections::groups::{batch_floor_kernels, box_floor_kernels};
use sections::{
    boxes::box_kernels,
    camera::{CameraData, Cameras, camera_kernels, differential_floor_kernels},
    camera_refs::camera_reference_kernels,
    cwbvh::{CwbvhData, cwbvh_kernels, print_leaks},
    groups::group_kernels,
    instance::{InstanceData, instance_kernels},
    patches::{PatchData, patch_kernels},
    quads::{QuadData, quad_kernels},
    spheres::{SphereData, sphere_group_kernels, sphere_kernels},
    sweep::{Sweep, sweep_kernels},
    traversal::{TraversalData, print_counts, print_traversal_leaks, traversal_kernels},
    triangles::triangle_kernels,
};

fn main() {
    let meshes = [cwbvh::Mesh::torus(250, 200), cwbvh::Mesh::icosphere(6)];
    if std::env::args().nth(1).as_deref() == Some("--leaks") {
        print_leaks(&meshes, 200_000);
        return;
    }
    // The section `traversal` runs on the same torus and icosphere, the
    // bunny, and the bunny split twice (16 triangles for each).
    let bunnies = [cwbvh::Mesh::bunny(0), cwbvh::Mesh::bunny(2)];
    let traversal_meshes: Vec<&cwbvh::Mesh> = meshes.iter().chain(&bunnies).collect();
    if std::env::args().nth(1).as_deref() == Some("--traversal-leaks") {
        print_traversal_leaks(&traversal_meshes, 50_000);
        return;
    }
    // `--same-order` and `--shuffle-all` (anywhere among the arguments):
    // see `harness::loops::Orders`.
    let mut args: Vec<String> = std::env::args().collect();
    let flag = |f: &str| args.iter().any(|a| a == f);
    let (same_order, shuffle_all) = (flag("--same-order"), flag("--shuffle-all"));
    args.retain(|a| a != "--same-order" && a != "--shuffle-all");
    let shuffle =
        |name: &str, boxes: bool| !same_order && (shuffle_all || !boxes) && name != "camera";
    let cwbvh_data: Vec<CwbvhData> = meshes.iter().map(|m| CwbvhData::new(m, 4096)).collect();
    let box_data: Vec<BoxData> = box_workloads()
        .into_iter()
        .map(|w| BoxData::new(w.name, w.rays, w.boxes, shuffle(w.name, true)))
        .collect();
    let tri_data: Vec<TriData> = triangle_workloads()
        .into_iter()
        .map(|w| TriData::new(w.name, w.rays, w.triangles, shuffle(w.name, false)))
        .collect();
    let sphere_data: Vec<SphereData> = rayhit_testkit::workloads::sphere_workloads()
        .into_iter()
        .map(|w| {
            let s = shuffle(w.name, false);
            SphereData::new(w, s)
        })
        .collect();
    let quad_data: Vec<QuadData> = rayhit_testkit::workloads::quad_workloads()
        .into_iter()
        .map(|w| {
            let s = shuffle(w.name, false);
            QuadData::new(w, s)
        })
        .collect();
    let patch_data: Vec<PatchData> = rayhit_testkit::workloads::patch_workloads()
        .into_iter()
        .map(|w| {
            let s = shuffle(w.name, false);
            PatchData::new(w, s)
        })
        .collect();
    let sphere_groups = rayhit_testkit::workloads::sphere_groups();
    let sphere_batches: Vec<rayhit::batch::SphereBatch> = sphere_groups
        .spheres
        .chunks(8)
        .map(|c| rayhit::batch::SphereBatch::from_slice(c).expect("8"))
        .collect();
    let sphere_prepared: Vec<rayhit::PreparedRay> = sphere_groups
        .rays
        .iter()
        .map(rayhit::PreparedRay::new)
        .collect();
    let groups = Groups::new();
    let (gb, gt) = (&groups.gb, &groups.gt);
    let sweep = Sweep::new();
    let cameras = CameraData::new();
    let camera_set = Cameras::of(&cameras);
    let instance_data = InstanceData::new();
    let traversal_data: Vec<TraversalData> = traversal_meshes
        .iter()
        .map(|m| TraversalData::new(m))
        .collect();

    let mut kernels = Vec::new();
    for d in &box_data {
        box_kernels(d, &mut kernels);
    }
    for d in &tri_data {
        triangle_kernels(d, &mut kernels);
    }
    for d in &sphere_data {
        sphere_kernels(d, &mut kernels);
    }
    for d in &quad_data {
        quad_kernels(d, &mut kernels);
    }
    for d in &patch_data {
        patch_kernels(d, &mut kernels);
    }
    sphere_group_kernels(
        &sphere_groups.rays,
        &sphere_prepared,
        &sphere_groups.spheres,
        &sphere_batches,
        &mut kernels,
    );
    group_kernels(
        gb,
        &groups.bb4,
        &groups.bb8,
        gt,
        &groups.tb4,
        &groups.tb8,
        &mut kernels,
    );
    #[cfg(target_arch = "x86_64")]
    box_floor_kernels(&groups, &mut kernels);
    #[cfg(target_arch = "x86_64")]
    batch_floor_kernels(gt, &groups.tb8, &groups.fb8, &mut kernels);
    sweep_kernels(&sweep, &mut kernels);
    for d in &cwbvh_data {
        cwbvh_kernels(d, &mut kernels);
    }
    camera_kernels(
        &camera_set,
        false,
        &cameras,
        ("camera", "camera differentials"),
        &mut kernels,
    );
    camera_reference_kernels(&cameras, &mut kernels);
    differential_floor_kernels(camera_set, &cameras, &mut kernels);
    camera_kernels(
        &camera_set,
        true,
        &cameras,
        ("camera, by reference", "camera differentials, by reference"),
        &mut kernels,
    );
    instance_kernels(&instance_data, &mut kernels);
    for d in &traversal_data {
        traversal_kernels(d, &mut kernels);
    }

    // `--count NAME WORKLOAD REPS`: run one row's loop REPS times, untimed,
    // and stop; under `valgrind --tool=callgrind`, the difference between
    // REPS = 10 and REPS = 0 over 10 x the row's tests is its instructions
    // per test.
    if let [_, flag, name, workload, reps] = args.as_slice()
        && flag == "--count"
    {
        let reps: u32 = reps.parse().expect("REPS is a number");
        let k = kernels
            .iter()
            .find(|k| &k.name == name && &k.workload == workload)
            .unwrap_or_else(|| panic!("no row {name:?} / {workload:?}"));
        let mut c = 0u64;
        for _ in 0..reps {
            c = c.wrapping_add(black_box((k.run)()));
        }
        println!("{} tests x {reps}: checksum {c}", k.tests);
        return;
    }

    // `--only SECTION`: time only the rows of the sections whose name
    // contains SECTION (a quick look while working on one kernel).
    if let [_, flag, section] = args.as_slice()
        && flag == "--only"
    {
        kernels.retain(|k| k.section.contains(section.as_str()));
    }

    let start = Instant::now();
    time_all(&mut kernels);
    let elapsed = start.elapsed();

    data::print_hit_rates(&box_data, &tri_data, &groups);
    harness::print_table(&kernels);
    if kernels
        .iter()
        .any(|k| k.section == sections::traversal::SECTION)
    {
        print_counts(&traversal_data);
    }
    targets::print_targets(&kernels);
    println!();
    println!(
        "{} kernels, {ROUNDS} rounds each, timed in {:.1} s; fastest round reported.",
        kernels.len(),
        elapsed.as_secs_f64()
    );
}
