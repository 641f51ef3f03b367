//! The PLY and USC-HairSalon `.data` strand readers on files built here byte by byte
//! (`support::strand_files`): every PLY layout in ASCII and both binary byte orders read back
//! exactly, the rules each bad file breaks named with its file and element, every truncation
//! refused without a panic, and a `.data` file's placeholder strands dropped and counted.

use crate::support::strand_files::{
    PLY_ENCODINGS, PLY_LAYOUTS, PlyElement, PlyEncoding, PlyLayout, hairsalon_bytes, ply_bytes,
    strands_ply, vertex_element,
};
use glam::Vec3;
use wisp::groom::{GroomOptions, build_groom, synthetic_strands};
use wisp::hairstyle::Hairstyle;
use wisp::input::strand_file::{is_strand_file_name, parse_strand_file};
use wisp::input::strands::{StrandFile, StrandFileError};

/// Seven strands of 2 to 8 vertices (strand `i` keeps `2 + i` of a synthetic strand's 12):
/// every layout must cut the vertex list at the right places.
fn uneven_strands() -> Vec<Vec<Vec3>> {
    let f = synthetic_strands(7, 12);
    f.strands()
        .enumerate()
        .map(|(i, s)| s[..2 + i].to_vec())
        .collect()
}

fn flat(strands: &[Vec<Vec3>]) -> Vec<Vec3> {
    strands.iter().flatten().copied().collect()
}

fn lens(strands: &[Vec<Vec3>]) -> Vec<u32> {
    strands.iter().map(|s| s.len() as u32).collect()
}

/// The (element, rule) of a PLY error, checking that it names the file.
fn ply_error(r: Result<StrandFile, StrandFileError>, file: &str) -> (String, String) {
    match r {
        Err(StrandFileError::Ply {
            file: f,
            element,
            rule,
        }) => {
            assert_eq!(f, file);
            (element, rule)
        }
        other => panic!("expected a PLY element error, got {other:?}"),
    }
}

#[test]
fn every_ply_layout_and_encoding_reads_back_exactly() {
    let strands = uneven_strands();
    for layout in PLY_LAYOUTS {
        for encoding in PLY_ENCODINGS {
            let bytes = strands_ply(&strands, layout, encoding);
            let f = parse_strand_file(&bytes, "groom.ply")
                .unwrap_or_else(|e| panic!("{layout:?} {encoding:?}: {e}"));
            // Floats written as their bytes or their shortest round-trip text: read exactly.
            assert_eq!(f.points, flat(&strands), "{layout:?} {encoding:?}");
            assert_eq!(f.strand_points, lens(&strands), "{layout:?} {encoding:?}");
            // The per-vertex thickness is read past, not kept.
            assert_eq!(f.thickness, None);
        }
    }
}

#[test]
fn ply_doubles_other_elements_and_any_extension_read_too() {
    let strands = uneven_strands();
    let rows = flat(&strands)
        .iter()
        .map(|p| vec![p.x as f64, p.y as f64, p.z as f64, 200.0])
        .collect();
    // A face list before the vertices and a strand element with uchar counts: the faces are
    // read past; doubles holding f32 values narrow back to them exactly.
    let elements = [
        PlyElement::new(
            "face",
            &[("vertex_indices", "list uchar int")],
            vec![vec![3.0, 0.0, 1.0, 2.0], vec![0.0]],
        ),
        PlyElement::new(
            "vertex",
            &[
                ("x", "double"),
                ("y", "double"),
                ("z", "double"),
                ("red", "uchar"),
            ],
            rows,
        ),
        PlyElement::new(
            "curves",
            &[("num_vertices", "uchar")],
            lens(&strands).iter().map(|&n| vec![n as f64]).collect(),
        ),
    ];
    for encoding in PLY_ENCODINGS {
        let bytes = ply_bytes(encoding, &elements);
        // The `ply` signature picks the reader whatever the name.
        let f = parse_strand_file(&bytes, "scan.points").unwrap();
        assert_eq!(f.points, flat(&strands), "{encoding:?}");
        assert_eq!(f.strand_points, lens(&strands), "{encoding:?}");
    }
}

#[test]
fn ply_edges_chain_from_the_lower_index_whatever_their_order_and_direction() {
    let strands = uneven_strands();
    // The edges of the root-first strands, listed backwards and every other one reversed.
    let mut edges = Vec::new();
    let mut at = 0usize;
    for s in &strands {
        for k in 0..s.len() - 1 {
            let (a, b) = ((at + k) as f64, (at + k + 1) as f64);
            edges.push(if k % 2 == 0 { vec![a, b] } else { vec![b, a] });
        }
        at += s.len();
    }
    edges.reverse();
    let elements = [
        vertex_element(&strands, false),
        PlyElement::new(
            "segment",
            &[("vertex2", "uint"), ("vertex1", "uint")],
            edges,
        ),
    ];
    let f = parse_strand_file(&ply_bytes(PlyEncoding::BigEndian, &elements), "edges.ply").unwrap();
    assert_eq!(f.points, flat(&strands));
    assert_eq!(f.strand_points, lens(&strands));
}

#[test]
fn ply_strand_indices_group_interleaved_vertices_in_file_order() {
    // Two strands whose vertices alternate in the file, strand 5 first.
    let a: Vec<Vec3> = (0..4).map(|k| Vec3::new(0.0, -(k as f32), 0.0)).collect();
    let b: Vec<Vec3> = (0..4).map(|k| Vec3::new(1.0, -(k as f32), 0.5)).collect();
    let mut rows = Vec::new();
    for k in 0..4 {
        rows.push(vec![a[k].x as f64, a[k].y as f64, a[k].z as f64, 5.0]);
        rows.push(vec![b[k].x as f64, b[k].y as f64, b[k].z as f64, 2.0]);
    }
    let props = [
        ("x", "float"),
        ("y", "float"),
        ("z", "float"),
        ("curve", "short"),
    ];
    let bytes = ply_bytes(
        PlyEncoding::Ascii,
        &[PlyElement::new("vertex", &props, rows)],
    );
    let f = parse_strand_file(&bytes, "interleaved.ply").unwrap();
    assert_eq!(f.points, [a, b].concat());
    assert_eq!(f.strand_points, vec![4, 4]);
}

/// A PLY file of 3 vertices (0,0,0), (0,-1,0), (0,-2,0) with `extra` elements after them.
fn three_vertices(vertex_props: &[(&str, &str)], extra: Vec<PlyElement>) -> Vec<u8> {
    let rows = (0..3)
        .map(|k| {
            let mut r = vec![0.0, -(k as f64), 0.0];
            r.resize(vertex_props.len(), 0.0);
            r
        })
        .collect();
    let mut elements = vec![PlyElement::new("vertex", vertex_props, rows)];
    elements.extend(extra);
    ply_bytes(PlyEncoding::Ascii, &elements)
}

const XYZ: [(&str, &str); 3] = [("x", "float"), ("y", "float"), ("z", "float")];

fn edges(pairs: &[(u32, u32)]) -> PlyElement {
    let rows = pairs
        .iter()
        .map(|&(a, b)| vec![a as f64, b as f64])
        .collect();
    PlyElement::new("edge", &[("vertex1", "int"), ("vertex2", "int")], rows)
}

fn counts(name: &str, prop: &str, values: &[f64]) -> PlyElement {
    PlyElement::new(
        name,
        &[(prop, "int")],
        values.iter().map(|&v| vec![v]).collect(),
    )
}

#[test]
fn bad_ply_files_are_refused_naming_the_element_and_the_rule() {
    let with_index = [XYZ.as_slice(), &[("strand", "int")]].concat();
    let cases: Vec<(&str, Vec<u8>, &str, &str)> = vec![
        (
            "no y",
            three_vertices(&[("x", "float"), ("z", "float"), ("strand", "int")], vec![]),
            "vertex",
            "no property `y`",
        ),
        (
            "x a list",
            ply_bytes(
                PlyEncoding::Ascii,
                &[PlyElement::new(
                    "vertex",
                    &[("x", "list uchar float"), ("y", "float"), ("z", "float")],
                    vec![],
                )],
            ),
            "vertex",
            "`x` is a list",
        ),
        (
            "no vertex element",
            ply_bytes(PlyEncoding::Ascii, &[counts("strand", "count", &[2.0])]),
            "vertex",
            "no `vertex` element",
        ),
        (
            "no strand structure",
            three_vertices(&XYZ, vec![]),
            "vertex",
            "nothing says which vertices form a strand",
        ),
        (
            "a strand element without counts",
            three_vertices(&XYZ, vec![counts("strand", "length", &[3.0])]),
            "strand",
            "needs a vertex count",
        ),
        // 2 + 2 = 4 vertices announced for 3.
        (
            "counts over the vertices",
            three_vertices(&XYZ, vec![counts("strand", "vertex_count", &[2.0, 2.0])]),
            "strand",
            "add up to 4, but the `vertex` element has 3",
        ),
        (
            "a strand of 1 vertex by count",
            three_vertices(&XYZ, vec![counts("curve", "count", &[1.0, 2.0])]),
            "curve",
            "strand 0 has 1 vertices: a strand needs at least 2",
        ),
        // 0 segments: 1 vertex.
        (
            "a strand of 0 segments",
            three_vertices(&XYZ, vec![counts("strands", "segments", &[1.0, 0.0])]),
            "strands",
            "strand 1 has 0 segments, so 1 more vertices",
        ),
        (
            "a strand index with one vertex",
            {
                let mut b = three_vertices(&with_index, vec![]);
                // The third vertex's strand index 0 becomes 7 (the last digit of the file).
                let at = b.len() - 2;
                b[at] = b'7';
                b
            },
            "vertex",
            "strand index 7 has only vertex 2",
        ),
        (
            "a loop",
            three_vertices(&XYZ, vec![edges(&[(0, 1), (1, 2), (2, 0)])]),
            "edge",
            "vertex 0 is on a closed loop of edges",
        ),
        (
            "a vertex on no edge",
            three_vertices(&XYZ, vec![edges(&[(0, 1)])]),
            "edge",
            "vertex 2 is on no edge",
        ),
        (
            "an edge to a missing vertex",
            three_vertices(&XYZ, vec![edges(&[(0, 1), (1, 3)])]),
            "edge",
            "edge 1 joins vertices 1 and 3",
        ),
    ];
    for (what, bytes, element, rule) in cases {
        let (e, r) = ply_error(parse_strand_file(&bytes, "bad.ply"), "bad.ply");
        assert_eq!(e, element, "{what}: {r}");
        assert!(r.contains(rule), "{what}: {r}");
    }
    // Four vertices, vertex 1 on three edges.
    let star = ply_bytes(
        PlyEncoding::Ascii,
        &[
            PlyElement::new("vertex", &XYZ, vec![vec![0.0; 3]; 4]),
            edges(&[(0, 1), (1, 2), (1, 3)]),
        ],
    );
    let (_, r) = ply_error(parse_strand_file(&star, "star.ply"), "star.ply");
    assert!(r.contains("vertex 1 is on 3 edges"), "{r}");
    // The whole message names file, element and rule.
    let e = parse_strand_file(&star, "star.ply")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("star.ply: PLY element `edge`: vertex 1"),
        "{e}"
    );
}

#[test]
fn non_finite_ply_coordinates_are_refused_by_vertex() {
    let mut strands = uneven_strands();
    strands[1][1].y = f32::NAN; // vertex 2 + 1 = 3
    for encoding in PLY_ENCODINGS {
        let bytes = strands_ply(&strands, PlyLayout::StrandIndex, encoding);
        let (e, r) = ply_error(parse_strand_file(&bytes, "nan.ply"), "nan.ply");
        assert_eq!(e, "vertex");
        // ASCII `NaN` is no PLY number: the PLY reader refuses its line (10 header lines,
        // then vertices 0 to 3).
        let want = match encoding {
            PlyEncoding::Ascii => "its values cannot be read: Line 14",
            _ => "vertex 3 is not finite",
        };
        assert!(r.starts_with(want), "{encoding:?}: {r}");
    }
    // A double beyond the f32 range is not a coordinate wisp can keep.
    let rows = vec![vec![0.0, 1e300, 0.0, 0.0], vec![0.0, 0.0, 0.0, 0.0]];
    let props = [
        ("x", "double"),
        ("y", "double"),
        ("z", "double"),
        ("strand", "uchar"),
    ];
    let bytes = ply_bytes(
        PlyEncoding::LittleEndian,
        &[PlyElement::new("vertex", &props, rows)],
    );
    let (_, r) = ply_error(parse_strand_file(&bytes, "far.ply"), "far.ply");
    assert!(r.contains("vertex 0 is not finite"), "{r}");
}

#[test]
fn hostile_ply_headers_are_refused_before_the_payload_is_read() {
    let header = |count: &str| {
        format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {count}\nproperty float x\n\
             property float y\nproperty float z\nproperty int strand\nend_header\n"
        )
        .into_bytes()
    };
    // 4 billion vertices: over the cap of 100 million, whatever the file holds.
    let (e, r) = ply_error(
        parse_strand_file(&header("4000000000"), "huge.ply"),
        "huge.ply",
    );
    assert_eq!(e, "vertex");
    assert!(r.contains("over the limit of 100000000"), "{r}");
    // A million vertices of 16 bytes need 16 MB; the file has 64 bytes after its header.
    let mut bytes = header("1000000");
    bytes.extend_from_slice(&[0u8; 64]);
    let (_, r) = ply_error(parse_strand_file(&bytes, "short.ply"), "short.ply");
    assert!(
        r.contains("at least 16000000 bytes; the file has 64 after its header"),
        "{r}"
    );
    // Not a PLY header: refused by the PLY reader with its message.
    for bad in [
        &b"ply\nformat binary_middle_endian 1.0\nend_header\n"[..],
        b"ply\n",
    ] {
        match parse_strand_file(bad, "odd.ply") {
            Err(StrandFileError::PlyHeader { file, rule }) => {
                assert_eq!(file, "odd.ply");
                assert!(!rule.is_empty());
            }
            other => panic!("expected a PLY header error, got {other:?}"),
        }
    }
}

#[test]
fn every_truncation_of_a_ply_file_is_an_error_not_a_panic() {
    let strands: Vec<Vec<Vec3>> = uneven_strands().into_iter().take(3).collect();
    for layout in PLY_LAYOUTS {
        for encoding in PLY_ENCODINGS {
            let bytes = strands_ply(&strands, layout, encoding);
            assert!(parse_strand_file(&bytes, "t.ply").is_ok());
            // An ASCII file cut after its last digit still holds every value.
            let complete = bytes.len() - usize::from(encoding == PlyEncoding::Ascii);
            for cut in 0..complete {
                let r = parse_strand_file(&bytes[..cut], "t.ply");
                assert!(r.is_err(), "{layout:?} {encoding:?} cut at {cut} read");
            }
        }
    }
}

fn malformed(r: Result<StrandFile, StrandFileError>) -> (u64, String) {
    match r {
        Err(StrandFileError::Malformed { file, offset, rule }) => {
            assert!(file.ends_with(".data"), "{file}");
            (offset, rule)
        }
        other => panic!("expected a malformed-file error, got {other:?}"),
    }
}

#[test]
fn a_hairsalon_file_reads_back_and_its_placeholders_are_dropped_and_counted() {
    let f = synthetic_strands(60, 10);
    let mut strands: Vec<Vec<Vec3>> = f.strands().map(<[Vec3]>::to_vec).collect();
    // The dataset's bald scalp points: strands of 1 point (and one of none).
    strands.insert(5, vec![strands[5][0]]);
    strands.insert(20, vec![]);
    let bytes = hairsalon_bytes(&strands);
    // 4 + 62 counts of 4 bytes + 60 × 10 + 1 points of 12 bytes.
    assert_eq!(bytes.len(), 4 + 62 * 4 + 601 * 12);
    let read = parse_strand_file(&bytes, "strands00001.data").unwrap();
    assert_eq!(read.points, flat(&strands));
    assert_eq!(read.strand_points, lens(&strands));
    let g = build_groom(
        &[("strands00001.data".into(), read)],
        &Hairstyle::default_smooth(),
        &GroomOptions::default(),
    )
    .unwrap();
    assert_eq!(g.report.strands_read, 62);
    assert_eq!(g.report.strands_dropped, 2);
}

#[test]
fn bad_hairsalon_files_are_refused_at_the_offset_of_the_broken_rule() {
    let strands: Vec<Vec<Vec3>> = synthetic_strands(3, 4)
        .strands()
        .map(<[Vec3]>::to_vec)
        .collect();
    let good = hairsalon_bytes(&strands);
    // Every cut: an error at or before the cut.
    for cut in 0..good.len() {
        let (offset, rule) = malformed(parse_strand_file(&good[..cut], "cut.data"));
        assert!(
            offset <= cut as u64,
            "cut at {cut}: offset {offset} ({rule})"
        );
    }
    let with = |at: usize, v: i32| {
        let mut b = good.clone();
        b[at..at + 4].copy_from_slice(&v.to_le_bytes());
        b
    };
    // Strand 1's point count sits after strand 0's count and 4 points: byte 4 + 4 + 48.
    let cases = [
        (with(0, 0), 0, "strand count must be at least 1 (got 0)"),
        (with(0, -3), 0, "at least 1 (got -3)"),
        (
            with(0, i32::MAX),
            0,
            "strand count 2147483647 is over the limit of 2000000 strands",
        ),
        // At the strand cap, the counts alone need 8 MB: the file is far shorter.
        (with(0, 2_000_000), 4, "strand point counts: 2000000 items"),
        (
            with(56, -1),
            56,
            "strand 1: the point count must be at least 0 (got -1)",
        ),
        (with(56, 1 << 30), 60, "strand 1's points: 1073741824 items"),
        // Strand 1's second point's y (byte 60 + 12 + 4) as NaN.
        (
            with(76, f32::NAN.to_bits() as i32),
            72,
            "strand 1: point 1 is not finite",
        ),
        (
            [good.as_slice(), &[0u8; 3]].concat(),
            good.len() as u64,
            "3 bytes follow the last of the 3 strands",
        ),
    ];
    for (bytes, offset, rule) in cases {
        let (o, r) = malformed(parse_strand_file(&bytes, "bad.data"));
        assert!(r.contains(rule), "{r}");
        assert_eq!(o, offset, "{r}");
    }
}

#[test]
fn strand_file_names_are_told_by_extension_and_others_refused() {
    for name in ["a.tfx", "b.HAIR", "c.ply", "d.Ply", "strands00001.data"] {
        assert!(is_strand_file_name(name), "{name}");
    }
    for name in ["a.json", "b.abc", "ply", "data", "c.ply.json"] {
        assert!(!is_strand_file_name(name), "{name}");
    }
    let e = parse_strand_file(b"\0\0\0\0", "x.abc").unwrap_err();
    assert!(matches!(e, StrandFileError::UnknownFormat { .. }), "{e}");
    assert!(e.to_string().contains("`.ply`"), "{e}");
}
