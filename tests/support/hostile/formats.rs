//! The input formats under test, as a table: a name, valid seed files, how the entry file is
//! structured (for structural mutations), and a loader that says accepted or refused and
//! checks what an accepted input promises.
//!
//! To add a format, add one entry to
//! [`all`]: its seeds (valid files, the entry first) and a loader calling the library. The
//! mutators and the runner in `tests/lib/hostile_loaders.rs` then cover it with no further code.

use super::super::strand_files;
use super::Rng;
use super::mutate;
use serde_json::Value;
use std::path::{Path, PathBuf};
use wisp::hairstyle::Hairstyle;
use wisp::motion::{Fit, JointRef, MAX_POSE_DISTANCE_M, Motion, MotionOptions, SphereSpec};

/// How the entry file is structured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layout {
    /// JSON text: structural mutations apply.
    Json,
    /// GLB: a JSON chunk (structural mutations) and a binary chunk (float mutations).
    Glb,
    /// Opaque bytes.
    Binary,
    /// A simulation cache: edits of its fields and records with the checksums resealed
    /// (`cache::mutate`), or raw byte edits.
    Cache,
}

/// A file given to the loader in a special form instead of its bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Special {
    Missing,
    /// A symbolic link to `/dev/zero`.
    DevZero,
    Directory,
}

/// Files of one input: the entry first.
#[derive(Clone, Debug)]
pub struct Case {
    pub files: Vec<(String, Vec<u8>)>,
    pub special: Option<(usize, Special)>,
    /// Seed of the loader's own choices (options).
    pub option_seed: u64,
}

impl Case {
    /// Total bytes of the input.
    pub fn bytes(&self) -> usize {
        self.files.iter().map(|(_, b)| b.len()).sum()
    }

    /// Writes the files into `dir`; returns the entry's path.
    pub fn write(&self, dir: &Path) -> std::io::Result<PathBuf> {
        for (i, (name, bytes)) in self.files.iter().enumerate() {
            let p = dir.join(name);
            match self.special {
                Some((k, s)) if k == i => match s {
                    Special::Missing => {}
                    Special::DevZero => {
                        #[cfg(unix)]
                        std::os::unix::fs::symlink("/dev/zero", &p)?;
                    }
                    Special::Directory => std::fs::create_dir_all(&p)?,
                },
                _ => std::fs::write(&p, bytes)?,
            }
        }
        Ok(dir.join(&self.files[0].0))
    }
}

/// What the loader did with an input.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    Accepted,
    /// Refused with this message.
    Refused(String),
}

/// Loads a case in `dir` (an empty directory of its own); `Err` when a promise is broken.
pub type Loader = fn(&Case, &Path) -> Result<Verdict, String>;

pub struct Format {
    pub name: &'static str,
    pub layout: Layout,
    pub seeds: Vec<Case>,
    pub load: Loader,
}

/// Longest acceptable error message (some glTF errors were 11–13 KB).
pub const MAX_MESSAGE_CHARS: usize = 1500;

/// Checks a refusal's message: names the file, short, one prefix.
fn refused(message: String, file: &str) -> Result<Verdict, String> {
    if !message.contains(file) {
        return Err(format!("the message does not name {file}: {message}"));
    }
    if message.chars().count() > MAX_MESSAGE_CHARS {
        return Err(format!(
            "the message is {} characters: {}...",
            message.chars().count(),
            message.chars().take(300).collect::<String>()
        ));
    }
    if message.contains("invalid glTF: invalid glTF") {
        return Err(format!("the message repeats its prefix: {message}"));
    }
    Ok(Verdict::Refused(message))
}

fn file(name: &str, bytes: Vec<u8>) -> Case {
    Case {
        files: vec![(name.to_string(), bytes)],
        special: None,
        option_seed: 0,
    }
}

fn robot_glb() -> Option<Vec<u8>> {
    let p =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/animations/RobotExpressive.glb");
    std::fs::read(p).ok()
}

fn dance_glb() -> Vec<u8> {
    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("animations/dance.glb"))
        .expect("animations/dance.glb")
}

/// A .glb as a .gltf whose buffer 0 is `bin_name` (external) or a `data:` URI (embedded).
fn as_gltf(glb: &[u8], bin_name: Option<&str>) -> Case {
    let (mut json, bin) = mutate::split_glb(glb).expect("seed GLB is valid");
    let uri = match bin_name {
        Some(n) => n.to_string(),
        None => format!("data:application/octet-stream;base64,{}", base64(&bin)),
    };
    json["buffers"][0]["uri"] = Value::String(uri);
    let text = json.to_string().into_bytes();
    let mut case = file("seed.gltf", text);
    if let Some(n) = bin_name {
        case.files.push((n.to_string(), bin));
    }
    case
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Motion options drawn from the case's option seed: mostly defaults, sometimes odd.
fn motion_options(seed: u64) -> MotionOptions {
    let mut rng = Rng::new(seed);
    let mut o = MotionOptions::default();
    if rng.chance(0.15) {
        o.clip = Some(rng.pick(&["Dance", "nope", "", "#0"]).to_string());
    }
    if rng.chance(0.2) {
        o.head_joint = Some(match rng.below(4) {
            0 => JointRef::Index(rng.below(60)),
            1 => JointRef::Index(usize::MAX),
            2 => JointRef::Name("Head".into()),
            _ => JointRef::Name(String::new()),
        });
    }
    if rng.chance(0.15) {
        o.fit = Some(Fit {
            scale: *rng.pick(&[1.0, 1e-30, 1e30, 0.5, 0.0, -1.0]),
            offset_m: glam::Vec3::splat(*rng.pick(&[0.0, 0.1, 1e30])),
        });
    }
    if rng.chance(0.15) {
        o.body_spheres = Some(if rng.chance(0.5) {
            vec![]
        } else {
            vec![SphereSpec {
                joint: JointRef::Index(rng.below(8)),
                offset_m: glam::Vec3::ZERO,
                radius_m: *rng.pick(&[0.05, 1e30, 1e-30, 0.0]),
            }]
        });
    }
    if rng.chance(0.2) {
        o.speed = *rng.pick(&[-1.0, 0.0, 1e-30, 1e30, 2.5, f32::MAX]);
    }
    o
}

/// What an accepted motion promises: finite poses at any time, and the head within
/// [`MAX_POSE_DISTANCE_M`] on a uniform grid of the clip.
fn check_motion(m: &Motion) -> Result<(), String> {
    let mut pose = wisp::motion::Pose::default();
    for t in [0.0f32, 0.37, 1.0, 2.5, 7.9, -3.0, 1e6, f32::MAX] {
        m.sample_into(t, &mut pose);
        if !pose.head.is_finite() || pose.spheres.iter().any(|s| !s.center.is_finite()) {
            return Err(format!("accepted, but the pose at t = {t} s is not finite"));
        }
    }
    let speed = if m.speed() != 0.0 { m.speed() } else { 1.0 };
    for i in 0..=20 {
        let t = m.duration_s() * i as f32 / 20.0 / speed;
        m.sample_into(t, &mut pose);
        let d = glam::Vec3::from(pose.head.translation).length();
        if d > MAX_POSE_DISTANCE_M * 1.001 {
            return Err(format!("accepted, but the head is {d} m away at t = {t} s"));
        }
    }
    Ok(())
}

fn load_hairstyle(case: &Case, _dir: &Path) -> Result<Verdict, String> {
    let name = "hostile.json";
    match Hairstyle::from_bytes(&case.files[0].1, name) {
        Ok(style) => {
            style
                .validate()
                .map_err(|e| format!("accepted but invalid: {e:?}"))?;
            // An accepted hairstyle has a finite budget estimate.
            let est = wisp::engine::estimate(
                &style,
                &Motion::still(glam::Affine3A::IDENTITY),
                &wisp::engine::EngineConfig::default(),
                &wisp::budget::RunPlan::default(),
            );
            if !est.work_cpu_s().is_finite() {
                return Err(format!(
                    "accepted, but its work estimate is {}",
                    est.work_cpu_s()
                ));
            }
            Ok(Verdict::Accepted)
        }
        Err(e) => refused(e.to_string(), name),
    }
}

fn load_glb(case: &Case, _dir: &Path) -> Result<Verdict, String> {
    let name = "hostile.glb";
    let opts = motion_options(case.option_seed);
    match Motion::from_glb_bytes(&case.files[0].1, name, &opts) {
        Ok(m) => check_motion(&m).map(|_| Verdict::Accepted),
        Err(e) => refused(e.to_string(), name),
    }
}

fn load_gltf_files(case: &Case, dir: &Path) -> Result<Verdict, String> {
    let entry = case
        .write(dir)
        .map_err(|e| format!("cannot write the case: {e}"))?;
    let opts = motion_options(case.option_seed);
    match Motion::load(&entry, &opts) {
        Ok(m) => check_motion(&m).map(|_| Verdict::Accepted),
        Err(e) => refused(e.to_string(), &case.files[0].0),
    }
}

/// What an accepted cache promises: every record reads back, each position finite.
fn load_cache(case: &Case, dir: &Path) -> Result<Verdict, String> {
    let entry = case
        .write(dir)
        .map_err(|e| format!("cannot write the case: {e}"))?;
    let name = &case.files[0].0;
    let motion = Motion::default_dance();
    let outcome =
        wisp::cache::CacheReader::open(&entry, &super::cache::expected()).and_then(|mut reader| {
            reader.read_settled(&motion)?;
            for i in 0..reader.header().frames {
                let p = reader.read_frame(i, &motion)?;
                if let Some(q) = p.iter().find(|q| !q.is_finite()) {
                    return Ok(Some(format!("accepted, but frame {i} has a position {q}")));
                }
            }
            Ok(None)
        });
    match outcome {
        Ok(None) => Ok(Verdict::Accepted),
        Ok(Some(broken)) => Err(broken),
        Err(e) => refused(e.to_string(), name),
    }
}

/// What an accepted strand file promises: it imports as a groom (or is refused by the import
/// with a message naming it), and an imported groom has finite guides and offsets.
fn load_strands(case: &Case, _dir: &Path) -> Result<Verdict, String> {
    let name = case.files[0].0.clone();
    let strands = match wisp::input::strand_file::parse_strand_file(&case.files[0].1, &name) {
        Ok(s) => s,
        Err(e) => return refused(e.to_string(), &name),
    };
    let base = Hairstyle::default_smooth();
    let opts = wisp::groom::GroomOptions::default();
    match wisp::groom::build_groom(&[(name.clone(), strands)], &base, &opts) {
        Ok(g) => {
            let finite = g.guides.rest.iter().all(|p| p.is_finite())
                && g.layout.rest_offset.iter().all(|p| p.is_finite())
                && g.guides
                    .link_length_m
                    .iter()
                    .all(|l| l.is_finite() && *l > 0.0);
            if !finite {
                return Err("accepted, but the groom has non-finite guides or offsets".into());
            }
            if g.layout.rest_offset.len() != g.layout.count() * g.layout.points_per_strand {
                return Err("accepted, but the offsets do not match the strands".into());
            }
            Ok(Verdict::Accepted)
        }
        Err(e) => refused(e.to_string(), &name),
    }
}

/// `wisp::groom::synthetic_strands` as one list of points per strand.
fn synthetic_strand_lists(count: usize, points: usize) -> Vec<Vec<glam::Vec3>> {
    let f = wisp::groom::synthetic_strands(count, points);
    f.strands().map(<[glam::Vec3]>::to_vec).collect()
}

/// PLY seeds: every strand layout in little-endian binary, and ASCII with strand indices.
fn ply_seeds() -> Vec<Case> {
    use strand_files::{PLY_LAYOUTS, PlyEncoding, strands_ply};
    let strands = synthetic_strand_lists(60, 8);
    let mut seeds: Vec<Case> = PLY_LAYOUTS
        .iter()
        .map(|&l| {
            file(
                "hostile.ply",
                strands_ply(&strands, l, PlyEncoding::LittleEndian),
            )
        })
        .collect();
    seeds.push(file(
        "hostile.ply",
        strands_ply(&strands, PLY_LAYOUTS[0], PlyEncoding::Ascii),
    ));
    seeds
}

/// A cyHair seed: the exporter's own output for a synthetic groom.
fn cyhair_seed() -> Vec<u8> {
    let f = wisp::groom::synthetic_strands(60, 8);
    // One directory per call: the tests of a binary build their formats in parallel.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("wisp-hostile-seed-{}-{call}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("seed.hair");
    wisp::export::cyhair::write_hair(&path, &f.points, 8, 0.01, "hostile seed")
        .expect("seed written");
    let bytes = std::fs::read(&path).expect("seed read");
    let _ = std::fs::remove_dir_all(&dir);
    bytes
}

/// A hairstyle with only the required fields.
const MINIMAL_HAIRSTYLE: &str = r#"{"name": "min", "head": {"radii_m": [0.08, 0.1, 0.09]},
 "scalp": {"max_polar_deg": 100, "front_polar_deg": 50},
 "wisps": {"count": 4, "radius_m": 0.01, "strands_per_wisp": 2},
 "guides": {"links": 3, "length_m": 0.1}, "strands": {"points": 4, "fibers_per_strand": 10}}"#;

/// Every format under test.
pub fn all() -> Vec<Format> {
    let dance = dance_glb();
    let robot = robot_glb();
    if robot.is_none() {
        println!("skipped: RobotExpressive.glb seeds (../shared/data is absent)");
    }
    let mut glb_seeds = vec![file("seed.glb", dance.clone())];
    let mut external = vec![as_gltf(&dance, Some("dance.bin"))];
    if let Some(r) = &robot {
        glb_seeds.push(file("seed.glb", r.clone()));
        external.push(as_gltf(r, Some("robot data.bin")));
    }
    vec![
        Format {
            name: "hairstyle JSON",
            layout: Layout::Json,
            seeds: vec![
                file(
                    "seed.json",
                    wisp::hairstyle::SMOOTH_JSON.as_bytes().to_vec(),
                ),
                file("seed.json", wisp::hairstyle::CURLY_JSON.as_bytes().to_vec()),
                file("seed.json", MINIMAL_HAIRSTYLE.as_bytes().to_vec()),
            ],
            load: load_hairstyle,
        },
        Format {
            name: "glTF binary (.glb)",
            layout: Layout::Glb,
            seeds: glb_seeds,
            load: load_glb,
        },
        Format {
            name: "glTF JSON with an external .bin",
            layout: Layout::Json,
            seeds: external,
            load: load_gltf_files,
        },
        Format {
            name: "glTF JSON with an embedded base64 buffer",
            layout: Layout::Json,
            seeds: vec![as_gltf(&dance, None)],
            load: load_gltf_files,
        },
        Format {
            name: "simulation cache",
            layout: Layout::Cache,
            seeds: vec![file("hostile.wcache", super::cache::seed())],
            load: load_cache,
        },
        Format {
            name: "TressFX strands (.tfx 3.x and 4.x)",
            layout: Layout::Binary,
            seeds: {
                let f = wisp::groom::synthetic_strands(60, 8);
                let strands: Vec<Vec<glam::Vec3>> = f.strands().map(|s| s.to_vec()).collect();
                vec![
                    file("hostile.tfx", wisp::input::tfx::encode_tfx3(&strands)),
                    file("hostile.tfx", wisp::input::tfx::encode_tfx4(&strands)),
                ]
            },
            load: load_strands,
        },
        Format {
            name: "cyHair strands (.hair)",
            layout: Layout::Binary,
            seeds: vec![file("hostile.hair", cyhair_seed())],
            load: load_strands,
        },
        Format {
            name: "PLY strands (.ply, each layout, ASCII and binary)",
            layout: Layout::Binary,
            seeds: ply_seeds(),
            load: load_strands,
        },
        Format {
            name: "USC-HairSalon strands (.data)",
            layout: Layout::Binary,
            seeds: vec![file(
                "hostile.data",
                strand_files::hairsalon_bytes(&synthetic_strand_lists(60, 8)),
            )],
            load: load_strands,
        },
    ]
}

/// A mutated copy of one of `format`'s seeds (1 to 3 mutations) and what was done.
pub fn mutated(format: &Format, rng: &mut Rng) -> (Case, Vec<String>) {
    let mut case = rng.pick(&format.seeds).clone();
    case.option_seed = rng.next_u64();
    let mut done = Vec::new();
    for _ in 0..1 + rng.below(3) {
        let k = if case.files.len() > 1 && rng.chance(0.3) {
            1 + rng.below(case.files.len() - 1)
        } else {
            0
        };
        if k > 0 && rng.chance(0.15) {
            let s = *rng.pick(&[Special::Missing, Special::DevZero, Special::Directory]);
            case.special = Some((k, s));
            done.push(format!("{} made {s:?}", case.files[k].0));
            continue;
        }
        let bytes = &mut case.files[k].1;
        let what = match (k, format.layout) {
            (0, Layout::Json) if rng.chance(0.75) => match serde_json::from_slice::<Value>(bytes) {
                Ok(mut v) => {
                    let d = mutate::json(rng, &mut v);
                    *bytes = mutate::to_text(&v).into_bytes();
                    d
                }
                Err(_) => mutate::bytes(rng, bytes),
            },
            (0, Layout::Glb) if rng.chance(0.7) => match mutate::split_glb(bytes) {
                Some((mut v, mut bin)) => {
                    let d = if rng.chance(0.7) {
                        mutate::json(rng, &mut v)
                    } else {
                        format!("BIN chunk: {}", mutate::floats(rng, &mut bin))
                    };
                    *bytes = mutate::make_glb(&mutate::to_text(&v), &bin);
                    d
                }
                None => mutate::bytes(rng, bytes),
            },
            (0, Layout::Cache) if rng.chance(0.7) => super::cache::mutate(rng, bytes),
            (_, _) if k > 0 && rng.chance(0.5) => mutate::floats(rng, bytes),
            _ => mutate::bytes(rng, bytes),
        };
        done.push(format!("{}: {what}", case.files[k].0));
    }
    (case, done)
}
