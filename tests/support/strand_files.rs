//! Strand files built in code, byte by byte, independently of wisp's readers: PLY (ASCII and
//! binary of both byte orders, in the strand layouts `wisp::input::ply` reads) and
//! USC-HairSalon `.data`.

use glam::Vec3;

/// How a PLY file's payload is encoded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlyEncoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

pub const PLY_ENCODINGS: [PlyEncoding; 3] = [
    PlyEncoding::Ascii,
    PlyEncoding::LittleEndian,
    PlyEncoding::BigEndian,
];

/// One PLY element: its properties as (name, type as the header writes it: `float`,
/// `list uchar int`, ...) and its rows. A row holds the values in property order; a list
/// property takes its length, then that many values.
#[derive(Clone, Debug)]
pub struct PlyElement {
    pub name: String,
    pub props: Vec<(String, String)>,
    pub rows: Vec<Vec<f64>>,
}

impl PlyElement {
    pub fn new(name: &str, props: &[(&str, &str)], rows: Vec<Vec<f64>>) -> Self {
        PlyElement {
            name: name.to_string(),
            props: props
                .iter()
                .map(|(n, t)| (n.to_string(), t.to_string()))
                .collect(),
            rows,
        }
    }
}

/// The bytes of a PLY file holding `elements` in `encoding`.
pub fn ply_bytes(encoding: PlyEncoding, elements: &[PlyElement]) -> Vec<u8> {
    let format = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::LittleEndian => "binary_little_endian",
        PlyEncoding::BigEndian => "binary_big_endian",
    };
    let mut text = format!("ply\nformat {format} 1.0\ncomment written by wisp's tests\n");
    for e in elements {
        text += &format!("element {} {}\n", e.name, e.rows.len());
        for (name, ty) in &e.props {
            text += &format!("property {ty} {name}\n");
        }
    }
    text += "end_header\n";
    let mut out = text.into_bytes();
    for e in elements {
        for row in &e.rows {
            let mut values = row.iter().copied();
            let mut words = Vec::new();
            for (_, ty) in &e.props {
                let mut ty = ty.split_whitespace();
                match (ty.next(), ty.next(), ty.next()) {
                    (Some("list"), Some(len_ty), Some(item_ty)) => {
                        let n = values.next().expect("list length");
                        put(&mut out, &mut words, encoding, len_ty, n);
                        for _ in 0..n as usize {
                            let v = values.next().expect("list item");
                            put(&mut out, &mut words, encoding, item_ty, v);
                        }
                    }
                    (Some(scalar), None, None) => {
                        let v = values.next().expect("value");
                        put(&mut out, &mut words, encoding, scalar, v);
                    }
                    _ => panic!("bad property type"),
                }
            }
            if encoding == PlyEncoding::Ascii {
                out.extend_from_slice(words.join(" ").as_bytes());
                out.push(b'\n');
            }
        }
    }
    out
}

/// Appends `v` as PLY type `ty`: a word for ASCII (shortest round-trip text of the type),
/// bytes in the byte order otherwise.
fn put(out: &mut Vec<u8>, words: &mut Vec<String>, encoding: PlyEncoding, ty: &str, v: f64) {
    macro_rules! num {
        ($t:ty) => {{
            let x = v as $t;
            match encoding {
                PlyEncoding::Ascii => words.push(format!("{x}")),
                PlyEncoding::LittleEndian => out.extend_from_slice(&x.to_le_bytes()),
                PlyEncoding::BigEndian => out.extend_from_slice(&x.to_be_bytes()),
            }
        }};
    }
    match ty {
        "char" | "int8" => num!(i8),
        "uchar" | "uint8" => num!(u8),
        "short" | "int16" => num!(i16),
        "ushort" | "uint16" => num!(u16),
        "int" | "int32" => num!(i32),
        "uint" | "uint32" => num!(u32),
        "float" | "float32" => num!(f32),
        "double" | "float64" => num!(f64),
        _ => panic!("unknown PLY type {ty}"),
    }
}

/// How a PLY file says which vertices form a strand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlyLayout {
    /// A per-vertex `strand_id` (int).
    StrandIndex,
    /// A `strand` element with `vertex_count` (uint).
    Counts,
    /// A `curve` element with `segments` (ushort): vertices − 1.
    Segments,
    /// An `edge` element with `vertex1`, `vertex2` (int), root to tip.
    Edges,
}

pub const PLY_LAYOUTS: [PlyLayout; 4] = [
    PlyLayout::StrandIndex,
    PlyLayout::Counts,
    PlyLayout::Segments,
    PlyLayout::Edges,
];

/// The `vertex` element of `strands` (float x, y, z, and a per-vertex `thickness` that the
/// reader ignores), with a `strand_id` when `with_index`.
pub fn vertex_element(strands: &[Vec<Vec3>], with_index: bool) -> PlyElement {
    let mut props = vec![("x", "float"), ("y", "float"), ("z", "float")];
    props.push(("thickness", "float"));
    if with_index {
        props.push(("strand_id", "int"));
    }
    let mut rows = Vec::new();
    for (s, strand) in strands.iter().enumerate() {
        for p in strand {
            let mut row = vec![p.x as f64, p.y as f64, p.z as f64, 0.007];
            if with_index {
                row.push(s as f64);
            }
            rows.push(row);
        }
    }
    PlyElement::new("vertex", &props, rows)
}

/// A PLY file of `strands` in `layout` and `encoding`.
pub fn strands_ply(strands: &[Vec<Vec3>], layout: PlyLayout, encoding: PlyEncoding) -> Vec<u8> {
    let vertex = vertex_element(strands, layout == PlyLayout::StrandIndex);
    let lens = strands.iter().map(Vec::len);
    let second = match layout {
        PlyLayout::StrandIndex => None,
        PlyLayout::Counts => Some(PlyElement::new(
            "strand",
            &[("vertex_count", "uint")],
            lens.map(|n| vec![n as f64]).collect(),
        )),
        PlyLayout::Segments => Some(PlyElement::new(
            "curve",
            &[("segments", "ushort")],
            lens.map(|n| vec![n as f64 - 1.0]).collect(),
        )),
        PlyLayout::Edges => {
            let mut rows = Vec::new();
            let mut at = 0.0;
            for n in lens {
                for k in 0..n - 1 {
                    rows.push(vec![at + k as f64, at + k as f64 + 1.0]);
                }
                at += n as f64;
            }
            Some(PlyElement::new(
                "edge",
                &[("vertex1", "int"), ("vertex2", "int")],
                rows,
            ))
        }
    };
    let elements: Vec<PlyElement> = std::iter::once(vertex).chain(second).collect();
    ply_bytes(encoding, &elements)
}

/// USC-HairSalon `.data` bytes: i32 strand count, then per strand an i32 point count and its
/// f32 x, y, z (little endian).
pub fn hairsalon_bytes(strands: &[Vec<Vec3>]) -> Vec<u8> {
    let mut b = (strands.len() as i32).to_le_bytes().to_vec();
    for s in strands {
        b.extend_from_slice(&(s.len() as i32).to_le_bytes());
        for p in s {
            for v in p.to_array() {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    b
}
