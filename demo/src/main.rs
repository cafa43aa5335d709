//! The demo: a small ray tracer whose geometry is all `rayhit`.
//!
//! ```sh
//! cargo run --release -p rayhit-demo                 # writes render.png
//! cargo run --release -p rayhit-demo -- --scene leak # watertight vs Moller-Trumbore
//! cargo run --release -p rayhit-demo -- --scene shadows # segments to lights, glass
//! cargo run --release -p rayhit-demo -- --scene instances # one mesh placed far away
//! cargo run --release -p rayhit-demo -- --scene spheres  # spheres of every size, no epsilon
//! cargo run --release -p rayhit-demo -- --scene cornell  # the Cornell box, all quads
//! cargo run --release -p rayhit-demo -- --scene spheres --kernel textbook # the textbook's
//! cargo run --release -p rayhit-demo -- --lens 0.15,7.4 # depth of field
//! cargo run --release -p rayhit-demo -- --camera equirect --width 720 --height 360
//! cargo run --release -p rayhit-demo -- --help
//! ```
//!
//! The `demo` scene: primary rays from `PinholeCamera` (or, with
//! `--lens`, `--camera ortho` or `--camera equirect`, from
//! `ThinLensCamera`, `OrthographicCamera` or `EquirectangularCamera` on its
//! frame), with their ray differentials carried to the checkered ground
//! to filter its texture (`--filter`), a ground plane,
//! solid boxes, an icosphere and a torus of a few thousand triangles each
//! (bounding boxes and a small BVH tested with the prepared slab test before
//! any triangle), sunlight with soft shadows, sky light with ambient
//! occlusion and a mirror, every secondary ray spawned with
//! `SurfacePoint::spawn`.
//!
//! The `leak` scene: a closed box mesh whose vertices sit on pixel centres,
//! so that every camera ray runs through a shared edge or vertex; it is
//! traced once with the watertight `ray_triangle` and once with
//! `Triangle::moller_trumbore`, then made of bilinear patches (one through
//! the corners of each pair of triangles, curved with the tile) and traced
//! with `Patch::hit` and with Reshetov's textbook formulas; the rays that
//! get into the tile without any face reporting it are counted and drawn
//! in red (four panels, in that order).
//!
//! The `shadows` scene: a square light and two point lights, every shadow
//! ray a segment from `SurfacePoint::spawn_to` or `spawn_to_point` tested
//! with the interval and any-hit kernels, and a glass torus whose surfaces
//! each tint what is behind them, found in order along each ray by walking
//! consecutive intervals with `Triangle::hit` and `EdgeRule::OneHit` (see
//! `rayhit_demo::shadows`).
//!
//! The `instances` scene: one torus mesh placed many times by `Instance`s
//! (turned, squashed along random axes; two stacks of rings and a framed
//! mirror nested one level deeper), the whole scene and the camera 36,000
//! units from the origin; a two-level traversal (the instances' world
//! boxes from `object_to_world_box`, one `world_to_object` per visit),
//! hits carried out by `surface_to_world`, and every shadow, sky and
//! mirror ray from an instance started with `Instance::spawn_through` (see
//! `rayhit_demo::instances`).
//!
//! The `spheres` scene: a ground sphere of radius ten thousand, a moon
//! thirteen thousand units away, matte, glass and mirror spheres, and glass
//! droplets a thousandth of a unit across just in front of the lens, every
//! sphere tested with `Sphere::hit` (eight at a time) and every ray that
//! leaves one spawned from its surface point; `--kernel textbook` traces it
//! with the "One Weekend" quadratic and `t > 0.001` instead, which shows
//! acne on the ground and holes in the droplets (see
//! `rayhit_demo::spheres`).
//!
//! The `cornell` scene: the Cornell box of "The Next Week", every wall,
//! block face and the light a `Quad`, lit through shadow segments from
//! `spawn_to` to points sampled on the light, with two diffuse bounces
//! (see `rayhit_demo::cornell`).

use std::error::Error;
use std::fs::File;
use std::io::BufWriter;
use std::process::ExitCode;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use rayhit::Camera;
use rayhit::camera::{EquirectangularCamera, OrthographicCamera, ThinLensCamera};
use rayhit::glam::Vec3;
use rayhit_demo::cornell::{cornell_scene, render_cornell};
use rayhit_demo::demo::{Filter, Scene, Shape, View, demo_scene, render};
use rayhit_demo::instances::{Content, On, instance_scene, render_instances};
use rayhit_demo::leak::{PatchKernel, leak_scene};
use rayhit_demo::mesh::Kernel;
use rayhit_demo::renderer::to_srgb8;
use rayhit_demo::shadows::{render_shadows, shadow_scene};
use rayhit_demo::spheres::{self, render_spheres, sphere_scene};

const USAGE: &str = "\
usage: render [--scene demo|leak|shadows|instances|spheres|cornell]
              [--camera pinhole|ortho|equirect] [--lens RADIUS,FOCUS]
              [--filter differentials|cones|off] [--kernel rayhit|textbook]
              [--width N] [--height N] [--samples N] [--out FILE]

  --scene    demo (default): ground, boxes and meshes in soft sunlight
             leak: the watertightness experiment, both triangle kernels and
                   both patch kernels
             shadows: soft shadows from a square light and hard ones from
             two point lights, every shadow ray a segment between two
             points with no epsilon, and a glass torus that tints what is
             behind it once per surface crossed
             instances: one torus placed many times, turned, squashed and
             nested, far from the origin, with a mirror and sunlight, every
             ray leaving an instance spawned through the instance's map
             spheres: spheres from 1e-3 to 2e4 across, some ten thousand
             units away, glass, mirror and matte, with no epsilon
             cornell: the Cornell box, walls, blocks and light all quads,
             shadow segments to the light, two diffuse bounces
  --camera   the demo scene's camera (default pinhole): ortho, parallel
             rays from the pinhole's eye plane; equirect, the whole sphere
             around the eye
  --lens     a thin lens on the pinhole camera: its radius and the distance
             it is focused at, in world units (the scene's sphere is about
             7.4 away), for depth of field; try --lens 0.15,7.4
  --filter   the checkered ground's texture filter (default differentials):
             box-filtered over the pixel's footprint from ray
             differentials, or from ray cones, or point-sampled (off), which
             shows moire towards the horizon at one sample per pixel
  --kernel   the spheres scene's ray/sphere test (default rayhit):
             textbook, the One Weekend quadratic with t > 0.001 and new
             rays from the unmoved hit point, for comparison
  --width    image width in pixels (default 640; 4 to 16384)
  --height   image height in pixels (default 360; 4 to 16384)
  --samples  rays per pixel in the demo, shadows and instances scenes
             (default 16; the leak scene traces exactly one ray through
             each pixel centre)
  --out      the PNG to write (default render.png)";

/// The largest width or height accepted.
const MAX_SIZE: u32 = 16384;

/// Which camera the demo scene is seen through.
#[derive(Clone, Copy, Debug, PartialEq)]
enum CameraKind {
    Pinhole,
    Orthographic,
    Equirectangular,
}

/// Which scene is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
enum SceneKind {
    Demo,
    Leak,
    Shadows,
    Instances,
    Spheres,
    Cornell,
}

/// The command line.
#[derive(Debug)]
struct Options {
    scene: SceneKind,
    camera: CameraKind,
    lens: Option<(f32, f32)>,
    filter: Filter,
    kernel: spheres::Kernel,
    width: u32,
    height: u32,
    samples: u32,
    out: String,
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Option<Options>, String> {
    let mut options = Options {
        scene: SceneKind::Demo,
        camera: CameraKind::Pinhole,
        lens: None,
        filter: Filter::Differentials,
        kernel: spheres::Kernel::Rayhit,
        width: 640,
        height: 360,
        samples: 16,
        out: "render.png".to_owned(),
    };
    while let Some(flag) = args.next() {
        if flag == "-h" || flag == "--help" {
            return Ok(None);
        }
        let value = args.next().ok_or_else(|| format!("{flag} needs a value"))?;
        let number = |min: u32, max: u32| match value.parse::<u32>() {
            Ok(n) if (min..=max).contains(&n) => Ok(n),
            _ => Err(format!(
                "{flag} wants a whole number from {min} to {max}, not {value:?}"
            )),
        };
        match flag.as_str() {
            "--scene" => {
                options.scene = match value.as_str() {
                    "demo" => SceneKind::Demo,
                    "leak" => SceneKind::Leak,
                    "shadows" => SceneKind::Shadows,
                    "instances" => SceneKind::Instances,
                    "spheres" => SceneKind::Spheres,
                    "cornell" => SceneKind::Cornell,
                    _ => {
                        return Err(format!(
                            "unknown scene {value:?}: demo, leak, shadows, instances, spheres \
                             or cornell"
                        ));
                    }
                }
            }
            "--camera" => {
                options.camera = match value.as_str() {
                    "pinhole" => CameraKind::Pinhole,
                    "ortho" => CameraKind::Orthographic,
                    "equirect" => CameraKind::Equirectangular,
                    _ => {
                        return Err(format!(
                            "unknown camera {value:?}: pinhole, ortho or equirect"
                        ));
                    }
                }
            }
            "--lens" => {
                let bad = || format!("--lens wants RADIUS,FOCUS (two numbers), not {value:?}");
                let (r, f) = value.split_once(',').ok_or_else(bad)?;
                let r: f32 = r.trim().parse().map_err(|_| bad())?;
                let f: f32 = f.trim().parse().map_err(|_| bad())?;
                options.lens = Some((r, f));
            }
            "--filter" => {
                options.filter = match value.as_str() {
                    "differentials" => Filter::Differentials,
                    "cones" => Filter::Cones,
                    "off" => Filter::Off,
                    _ => {
                        return Err(format!(
                            "unknown filter {value:?}: differentials, cones or off"
                        ));
                    }
                }
            }
            "--kernel" => {
                options.kernel = match value.as_str() {
                    "rayhit" => spheres::Kernel::Rayhit,
                    "textbook" => spheres::Kernel::Textbook,
                    _ => return Err(format!("unknown kernel {value:?}: rayhit or textbook")),
                }
            }
            "--width" => options.width = number(4, MAX_SIZE)?,
            "--height" => options.height = number(4, MAX_SIZE)?,
            "--samples" => options.samples = number(1, 1 << 16)?,
            "--out" => options.out = value,
            _ => return Err(format!("unknown flag {flag:?}")),
        }
    }
    if options.lens.is_some() && options.camera != CameraKind::Pinhole {
        return Err("--lens goes with the pinhole camera".to_owned());
    }
    Ok(Some(options))
}

/// The demo scene's view for the options: the pinhole camera, with a lens,
/// or an orthographic or equirectangular camera on its frame.
fn view(scene: &Scene, options: &Options) -> Result<View, String> {
    let cam = &scene.camera;
    let err = |e: rayhit::camera::CameraError| format!("camera: {e}");
    Ok(match (options.camera, options.lens) {
        (CameraKind::Pinhole, None) => Box::new(*cam),
        (CameraKind::Pinhole, Some((radius, focus))) => {
            Box::new(ThinLensCamera::new(*cam, radius, focus).map_err(err)?)
        }
        (CameraKind::Orthographic, _) => {
            // The pinhole's view at the target's distance: 4.5 units
            // across the image's height.
            let size = 4.5 / cam.height() as f32;
            Box::new(
                OrthographicCamera::new(
                    cam.eye(),
                    cam.forward(),
                    Vec3::Y,
                    size,
                    cam.width(),
                    cam.height(),
                )
                .map_err(err)?,
            )
        }
        (CameraKind::Equirectangular, _) => Box::new(
            EquirectangularCamera::new(
                cam.eye(),
                cam.forward(),
                Vec3::Y,
                cam.width(),
                cam.height(),
            )
            .map_err(err)?,
        ),
    })
}

fn progress_bar(rows: u32) -> ProgressBar {
    let style = ProgressStyle::with_template("{bar:40} {pos}/{len} rows  {elapsed}")
        .expect("a valid template")
        .progress_chars("##-");
    ProgressBar::new(u64::from(rows)).with_style(style)
}

/// Creates the output file (before the render, so that a bad path fails
/// at once).
fn create(path: &str) -> Result<File, String> {
    File::create(path).map_err(|e| format!("cannot write {path}: {e}"))
}

fn write_png(file: File, width: u32, height: u32, rgb: &[u8]) -> Result<(), Box<dyn Error>> {
    let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::High);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(())
}

fn report_speed(rays: u64, seconds: f64) {
    println!(
        "{rays} rays in {seconds:.2} s on {} threads: {:.2} M rays/s",
        rayon::current_num_threads(),
        rays as f64 / seconds / 1e6
    );
}

/// Renders a picture of the options' size with a progress bar over its
/// rows (`draw` gets the per-row callback and returns the linear pixels
/// and what else the scene reports), writes it to `file` as sRGB and says
/// so. Returns what `draw` reported and the seconds the render took.
fn render_png<T>(
    options: &Options,
    file: File,
    draw: impl FnOnce(&(dyn Fn() + Sync)) -> (Vec<Vec3>, T),
) -> Result<(T, f64), Box<dyn Error>> {
    let bar = progress_bar(options.height);
    let start = Instant::now();
    let (pixels, report) = draw(&|| bar.inc(1));
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let rgb: Vec<u8> = pixels.iter().flat_map(|&c| to_srgb8(c)).collect();
    write_png(file, options.width, options.height, &rgb)?;
    println!(
        "rendered {}x{} at {} samples per pixel into {}",
        options.width, options.height, options.samples, options.out
    );
    Ok((report, seconds))
}

fn run_demo(options: &Options) -> Result<(), Box<dyn Error>> {
    let file = create(&options.out)?;
    let mut scene = demo_scene(options.width, options.height);
    scene.view = view(&scene, options)?;
    scene.filter = options.filter;
    let objects: Vec<String> = scene
        .objects
        .iter()
        .map(|object| match &object.shape {
            Shape::Mesh(bvh) => format!("{} ({} triangles)", object.name, bvh.mesh.indices.len()),
            _ => object.name.to_owned(),
        })
        .collect();
    println!("scene: {}", objects.join(", "));
    let (rays, seconds) = render_png(options, file, |row_done| {
        let (image, rays) = render(&scene, options.samples, row_done);
        (image.pixels, rays)
    })?;
    report_speed(rays, seconds);
    Ok(())
}

fn run_spheres(options: &Options) -> Result<(), Box<dyn Error>> {
    let file = create(&options.out)?;
    let scene = sphere_scene(options.width, options.height, options.kernel);
    println!(
        "scene: {} spheres, radii {:e} to {:e}, the farthest centre {:.0} from the origin, \
         traced with the {:?} kernel",
        scene.balls.len(),
        scene
            .balls
            .iter()
            .map(|b| b.sphere.radius)
            .fold(f32::INFINITY, f32::min),
        scene
            .balls
            .iter()
            .map(|b| b.sphere.radius)
            .fold(0.0, f32::max),
        scene
            .balls
            .iter()
            .map(|b| b.sphere.center.length())
            .fold(0.0, f32::max),
        options.kernel
    );
    let (rays, seconds) = render_png(options, file, |row_done| {
        render_spheres(&scene, options.samples, row_done)
    })?;
    report_speed(rays, seconds);
    Ok(())
}

fn run_cornell(options: &Options) -> Result<(), Box<dyn Error>> {
    let file = create(&options.out)?;
    let scene = cornell_scene(options.width, options.height);
    println!(
        "scene: the Cornell box, {} quads (walls, two blocks, the light)",
        scene.faces.len()
    );
    let ([rays, segments], seconds) = render_png(options, file, |row_done| {
        render_cornell(&scene, options.samples, row_done)
    })?;
    println!("{segments} shadow segments");
    report_speed(rays + segments, seconds);
    Ok(())
}

fn run_leak(options: &Options) -> Result<(), Box<dyn Error>> {
    let file = create(&options.out)?;
    let scene = leak_scene(options.width, options.height);
    let (width, height) = (options.width, options.height);
    let bar = progress_bar(4 * height);
    let start = Instant::now();
    let [watertight, moller_trumbore] = Kernel::ALL.map(|kernel| scene.run(kernel, &|| bar.inc(1)));
    let [patches, reshetov] =
        PatchKernel::ALL.map(|kernel| scene.run_patches(kernel, &|| bar.inc(1)));
    let reports = [watertight, moller_trumbore, patches, reshetov];
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();

    // The four pictures side by side: the triangles, watertight and
    // Moller-Trumbore, then the patches, rayhit's and the textbook's.
    let gap = 8;
    let panels = reports.each_ref().map(|r| r.colours(&scene));
    let mut rgb = Vec::new();
    for j in 0..height as usize {
        for (k, panel) in panels.iter().enumerate() {
            if k > 0 {
                rgb.extend([255u8; 3].repeat(gap));
            }
            let row = &panel[j * width as usize..][..width as usize];
            rgb.extend(row.iter().flatten());
        }
    }
    let total_width = 4 * width + 3 * gap as u32;
    write_png(file, total_width, height, &rgb)?;

    println!(
        "closed mesh of {} triangles, or {} bilinear patches; {} pixel-centre rays enter it \
         exactly through a shared vertex",
        scene.mesh.mesh.indices.len(),
        scene.patches.patches.len(),
        reports[0].entering
    );
    for r in &reports {
        println!(
            "{:<36} leaked {:>6} of {} rays ({} of them through the whole mesh)",
            r.name, r.leaked, r.entering, r.escaped
        );
    }
    println!(
        "wrote {total_width}x{height} to {} (left to right: watertight and Moller-Trumbore \
         triangles, rayhit's and Reshetov's patches; red: leaked into the mesh, yellow: leaked \
         through it)",
        options.out
    );
    report_speed(4 * u64::from(width * height), seconds);
    Ok(())
}

fn run_shadows(options: &Options) -> Result<(), Box<dyn Error>> {
    let file = create(&options.out)?;
    let scene = shadow_scene(options.width, options.height);
    println!(
        "scene: ground, sphere, box, glass torus ({} triangles), a square light and {} point lights",
        scene.glass.mesh.indices.len(),
        scene.points.len()
    );
    let ((rays, segments, crossings), seconds) = render_png(options, file, |row_done| {
        let (image, rays, segments) = render_shadows(&scene, options.samples, row_done);
        (image.pixels, (rays, segments, image.crossings))
    })?;
    let mut counts = [0u32; 5];
    for &c in &crossings {
        counts[c.min(4)] += 1;
    }
    println!(
        "pixel-centre rays crossing the glass 0, 1, 2, 3, 4+ times: {counts:?}; {segments} shadow segments"
    );
    report_speed(rays + segments, seconds);
    Ok(())
}

fn run_instances(options: &Options) -> Result<(), Box<dyn Error>> {
    let file = create(&options.out)?;
    let scene = instance_scene(options.width, options.height);
    let triangles: Vec<usize> = scene.meshes.iter().map(|m| m.mesh.indices.len()).collect();
    let groups = scene
        .nodes
        .iter()
        .filter(|n| matches!(n.content, Content::Group(_)))
        .count();
    println!(
        "scene: ground, {} placed meshes (a torus of {} triangles, a slab of {}) under {} \
         top-level instances ({groups} of them groups), around {}",
        scene.paths().len(),
        triangles[0],
        triangles[1],
        scene.nodes.len(),
        scene.camera.eye()
    );
    let ((rays, instanced), seconds) = render_png(options, file, |row_done| {
        let (image, rays) = render_instances(&scene, options.samples, row_done);
        let instanced = image
            .seen
            .iter()
            .filter(|s| matches!(s, Some(On::Instance { .. })))
            .count();
        (image.pixels, (rays, instanced))
    })?;
    println!("{instanced} pixel centres see an instance");
    report_speed(rays, seconds);
    Ok(())
}

fn main() -> ExitCode {
    let options = match parse(std::env::args().skip(1)) {
        Ok(Some(options)) => options,
        Ok(None) => {
            println!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(message) => {
            eprintln!("render: {message}\n\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    let result = match options.scene {
        SceneKind::Demo => run_demo(&options),
        SceneKind::Leak => run_leak(&options),
        SceneKind::Shadows => run_shadows(&options),
        SceneKind::Instances => run_instances(&options),
        SceneKind::Spheres => run_spheres(&options),
        SceneKind::Cornell => run_cornell(&options),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("render: {error}");
            ExitCode::FAILURE
        }
    }
}
