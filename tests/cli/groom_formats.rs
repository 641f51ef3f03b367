//! `wisp render --hairstyle` with the PLY and USC-HairSalon `.data` strand files a user brings:
//! one frame renders with the groom's figures on stderr, and the hair alone covers a good part
//! of the picture.

use crate::support::scratch_dir;
use crate::support::strand_files::{PlyEncoding, PlyLayout, hairsalon_bytes, strands_ply};
use crate::{stderr, wisp};
use glam::Vec3;
use std::path::Path;

/// `wisp render --hairstyle HAIRSTYLE` of one 96×96 frame into `out`, with `extra` flags.
fn render_96(hairstyle: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut a = vec![
        "render",
        "--hairstyle",
        hairstyle,
        "--frames",
        "1",
        "--width",
        "96",
        "--height",
        "96",
        "--out",
        out.to_str().unwrap(),
    ];
    a.extend_from_slice(extra);
    wisp(&a)
}

/// Share of the 96×96 frame's pixels that differ from its top-left corner (the background).
fn hair_share(png_path: &Path) -> f64 {
    let differ = covered(png_path);
    differ.iter().filter(|d| **d).count() as f64 / differ.len() as f64
}

/// Width and height, pixels, of the box around the 96×96 frame's pixels that differ from its
/// top-left corner.
fn covered_box(png_path: &Path) -> (usize, usize) {
    let differ = covered(png_path);
    let (mut lo, mut hi) = ((96, 96), (0, 0));
    for (i, _) in differ.iter().enumerate().filter(|(_, d)| **d) {
        let (x, y) = (i % 96, i / 96);
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x), hi.1.max(y));
    }
    (hi.0.saturating_sub(lo.0) + 1, hi.1.saturating_sub(lo.1) + 1)
}

/// Which pixels of the 96×96 frame differ from its top-left corner, row by row.
fn covered(png_path: &Path) -> Vec<bool> {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(png_path).unwrap_or_else(|e| panic!("{}: {e}", png_path.display())),
    ));
    let mut reader = decoder.read_info().expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("png data");
    assert_eq!((info.width, info.height), (96, 96));
    let channels = info.color_type.samples();
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks_exact(channels).collect();
    let corner = px[0];
    px.iter()
        .map(|p| p.iter().zip(corner).any(|(a, b)| a.abs_diff(*b) > 8))
        .collect()
}

#[test]
fn a_ply_and_a_hairsalon_groom_render_one_frame() {
    let dir = scratch_dir("cli-groom-formats");
    let strands: Vec<Vec<Vec3>> = wisp::groom::synthetic_strands(300, 12)
        .strands()
        .map(<[Vec3]>::to_vec)
        .collect();
    let files = [
        (
            "groom.ply",
            strands_ply(&strands, PlyLayout::Counts, PlyEncoding::LittleEndian),
        ),
        ("groom.data", hairsalon_bytes(&strands)),
    ];
    for (name, bytes) in files {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let out = dir.join(format!("frames-{name}"));
        let o = wisp(&[
            "render",
            "--hairstyle",
            path.to_str().unwrap(),
            "--frames",
            "1",
            "--width",
            "96",
            "--height",
            "96",
            "--no-solids",
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = stderr(&o);
        assert!(o.status.success(), "{name}: {err}");
        // All 300 strands kept (none is zero length). Fewer than smooth's 3,350 render
        // strands: a sparse groom, in wisps of at least 3 strands, densified (densify.rs).
        assert!(
            err.contains("300 strands (0 dropped: zero length) in "),
            "{name}: {err}"
        );
        // Hair only (--no-solids), and the camera frames it: like the library's cyHair test,
        // at least a twentieth of the picture is hair (measured: 0.34).
        let share = hair_share(&out.join("frame_00000.png"));
        assert!(share > 0.05, "{name}: hair on {share:.3} of the frame");
    }
}

#[test]
fn fur_is_refused_naming_the_flag_that_keeps_it_as_authored() {
    let dir = scratch_dir("cli-groom-as-authored");
    // 1,000 strands of 4 points, 3 cm long, over a 30 cm ball 50 cm up: fur, in centimetres.
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    let strands: Vec<Vec<Vec3>> = (0..1000)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / 1000.0;
            let r = (1.0 - y * y).sqrt();
            let a = golden * i as f32;
            let d = Vec3::new(r * a.cos(), y, r * a.sin());
            (0..4)
                .map(|k| Vec3::new(0.0, 50.0, 0.0) + d * (15.0 + k as f32))
                .collect()
        })
        .collect();
    let path = dir.join("fur.ply");
    std::fs::write(
        &path,
        strands_ply(&strands, PlyLayout::Counts, PlyEncoding::LittleEndian),
    )
    .unwrap();
    let out = dir.join("frames");
    let run = |extra: &[&str]| render_96(path.to_str().unwrap(), &out, extra);
    let o = run(&[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--groom-as-authored"), "{}", stderr(&o));
    let o = run(&["--groom-as-authored"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("kept as authored at 0.01 m a unit (guessed"),
        "{}",
        stderr(&o)
    );
    assert!(hair_share(&out.join("frame_00000.png")) > 0.05);
    // The unit needs the mode.
    let o = run(&["--groom-unit-m", "0.01"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn fur_kept_as_authored_on_its_character_follows_its_bones() {
    let dir = scratch_dir("cli-groom-on-character");
    let dance = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("animations/dance.glb");
    // Fur on every 2nd vertex of the dance's own character, in its frame and metres.
    let motion = wisp::motion::Motion::load(&dance, &wisp::motion::MotionOptions::default())
        .expect("the dance loads");
    let rest = motion.character().expect("a character").rest_positions();
    let fur = wisp::groom::synthetic_fur(rest, 2, 0.015);
    let path = dir.join("fur.hair");
    let points = wisp::groom::FUR_POINTS;
    wisp::export::cyhair::write_hair(&path, &fur.points, points, 5e-5, "fur").unwrap();
    let out = dir.join("frames");
    let o = wisp(&[
        "render",
        "--animation",
        dance.to_str().unwrap(),
        "--hairstyle",
        path.to_str().unwrap(),
        "--groom-as-authored",
        "--frames",
        "2",
        "--start-s",
        "3.7",
        "--width",
        "96",
        "--height",
        "96",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("kept as authored at 1 m a unit"), "{err}");
    assert!(err.contains("pinned to the nearest of its bones"), "{err}");
    // The whole figure is framed, not the head: a standing body, taller than wide with its
    // arms out (82 × 46 px measured), where a head close-up fills the frame.
    let (w, h) = covered_box(&out.join("frame_00001.png"));
    assert!(h > 60 && 2 * h > 3 * w, "covered box {w}×{h} px");
}

/// A UV sphere of `radius_cm` at `centre_cm` as a TressFX `.tfxmesh` (one bone), and its
/// vertices and outward normals.
fn sphere_tfxmesh(centre_cm: Vec3, radius_cm: f32) -> (String, Vec<(Vec3, Vec3)>) {
    let (rings, sectors) = (12usize, 24usize);
    let mut verts = Vec::new();
    for r in 0..=rings {
        let polar = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..sectors {
            let az = std::f32::consts::TAU * s as f32 / sectors as f32;
            let n = Vec3::new(polar.sin() * az.cos(), polar.cos(), polar.sin() * az.sin());
            verts.push((centre_cm + n * radius_cm, n));
        }
    }
    let mut tris = Vec::new();
    for r in 0..rings {
        for s in 0..sectors {
            let (a, b) = (r * sectors + s, r * sectors + (s + 1) % sectors);
            let (c, d) = (a + sectors, b + sectors);
            tris.push([a, c, b]);
            tris.push([b, c, d]);
        }
    }
    let mut text =
        String::from("# TressFX collision mesh\nnumOfBones 1\n# bone index, bone name\n0 body\n");
    text += &format!(
        "numOfVertices {}\n# vertex index, position, normal, joints, weights\n",
        verts.len()
    );
    for (i, (p, n)) in verts.iter().enumerate() {
        text += &format!(
            "{i} {} {} {} {} {} {} 0 0 0 0 1 0 0 0\n",
            p.x, p.y, p.z, n.x, n.y, n.z
        );
    }
    text += &format!(
        "numOfTriangles {}\n# triangle index, vertex index 0, 1, 2\n",
        tris.len()
    );
    for (i, t) in tris.iter().enumerate() {
        text += &format!("{i} {} {} {}\n", t[0], t[1], t[2]);
    }
    (text, verts)
}

#[test]
fn a_groom_with_its_own_tfxmesh_is_drawn_on_it() {
    let dir = scratch_dir("cli-groom-own-mesh");
    // A furry ball in centimetres: a 30 cm sphere 50 cm up, 3 cm fur on every vertex.
    let (mesh, verts) = sphere_tfxmesh(Vec3::new(0.0, 50.0, 0.0), 30.0);
    let mesh_path = dir.join("ball.tfxmesh");
    std::fs::write(&mesh_path, mesh).unwrap();
    let strands: Vec<Vec<Vec3>> = verts
        .iter()
        .map(|(p, n)| (0..4).map(|k| *p + *n * k as f32).collect())
        .collect();
    let fur = dir.join("fur.ply");
    std::fs::write(
        &fur,
        strands_ply(&strands, PlyLayout::Counts, PlyEncoding::LittleEndian),
    )
    .unwrap();
    let out = dir.join("frames");
    let hairstyle = format!("{},{}", fur.display(), mesh_path.display());
    let run = |extra: &[&str]| render_96(&hairstyle, &out, extra);
    // Under white ambient light the grey ball shows between its fur (the key light's side is
    // shadowed by the fur: 312 strands carry a head of hair's fibres).
    let o = run(&["--groom-as-authored", "--ambient", "1,1,1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The ball is drawn under its fur and framed whole: round, most of the frame's height,
    // and more of the frame covered than by the fur alone (measured: 31% against 24%).
    let (w, h) = covered_box(&out.join("frame_00000.png"));
    assert!(h > 50 && w.abs_diff(h) * 5 < h, "covered box {w}×{h} px");
    let drawn = hair_share(&out.join("frame_00000.png"));
    let o = run(&["--groom-as-authored", "--ambient", "1,1,1", "--no-solids"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let fur_alone = hair_share(&out.join("frame_00000.png"));
    assert!(
        drawn > 0.25 && drawn > fur_alone + 0.04,
        "{drawn} against {fur_alone} for the fur alone"
    );
    // A mesh needs the groom kept as authored, and is the groom's only character.
    let o = run(&[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--groom-as-authored"), "{}", stderr(&o));
    let dance = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("animations/dance.glb");
    let o = run(&[
        "--groom-as-authored",
        "--animation",
        dance.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // A broken mesh is refused naming the file, line and rule (two vertices promised in a
    // file too short to hold them).
    std::fs::write(&mesh_path, "numOfBones 1\n0 body\nnumOfVertices 2\n0 1 2\n").unwrap();
    let o = run(&["--groom-as-authored"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("ball.tfxmesh: line 3: numOfVertices 2 is more than"),
        "{err}"
    );
}
