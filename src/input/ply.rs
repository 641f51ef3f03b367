//! PLY strand files (`.ply`) as capture and grooming tools write them: ASCII, binary little
//! and big endian, header and payload read by the `ply-rs-bw` crate.
//!
//! A `vertex` element holds the points (`x`, `y`, `z`: any scalar type, doubles narrowed to
//! f32); the strands are told by one of three layouts, tried in this order:
//!
//! 1. a strand element (`strand`, `strands`, `curve`, `curves`) with a per-strand vertex
//!    count (`vertex_count`, `num_vertices`, `num_points`, `point_count`, `count`; or
//!    `segments`, a strand of `segments + 1` vertices): the vertices, in file order, strand
//!    after strand; the counts must add up to the vertex count;
//! 2. a per-vertex strand index (`strand`, `strand_id`, `curve`, `curve_id`), an integer of
//!    any scalar type: the vertices of one index form a strand in file order, strands ordered
//!    by their first vertex;
//! 3. an edge element (`edge`, `edges`, `segment`, `segments`) with `vertex1` and `vertex2`:
//!    the edges chained into polylines, each started at its end with the lower vertex index
//!    (tools write the root first); a vertex on 3 edges (a branch), a closed loop and a vertex
//!    on no edge are refused.
//!
//! Every strand needs at least 2 vertices. Per-vertex `thickness`, `width`, `radius` and
//! colours, and every other element (a `face` list, say) are read past and ignored: the groom
//! builder uses only the points. Each element count is capped at [`MAX_ELEMENTS`] and checked
//! against the bytes after the header (an element needs at least its scalar sizes in binary,
//! 2 bytes a value in ASCII) before the payload is read, so a hostile header cannot make the
//! reader loop or allocate past the file. Errors name the file, the element and the rule.

use super::strands::{StrandFile, StrandFileError};
use crate::hairstyle::MAX_STRANDS;
use glam::Vec3;
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};
use std::collections::HashMap;

/// Most elements of one kind a file may declare (cyHair's cap on points).
pub const MAX_ELEMENTS: usize = 100_000_000;
/// Names of the per-vertex strand index.
pub const STRAND_INDEX_NAMES: [&str; 4] = ["strand", "strand_id", "curve", "curve_id"];
/// Names of a strand element and of its vertex count (`segments` counts one less).
pub const STRAND_ELEMENT_NAMES: [&str; 4] = ["strand", "strands", "curve", "curves"];
pub const VERTEX_COUNT_NAMES: [&str; 5] = [
    "vertex_count",
    "num_vertices",
    "num_points",
    "point_count",
    "count",
];
/// Names of an edge element (its properties are `vertex1` and `vertex2`).
pub const EDGE_ELEMENT_NAMES: [&str; 4] = ["edge", "edges", "segment", "segments"];

/// Parses a `.ply` file's bytes; `file` names it in errors.
pub fn parse_ply(bytes: &[u8], file: &str) -> Result<StrandFile, StrandFileError> {
    let ply = |element: &str, rule: String| StrandFileError::Ply {
        file: file.to_string(),
        element: element.to_string(),
        rule,
    };
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| StrandFileError::PlyHeader {
            file: file.to_string(),
            rule: short_message(&e),
        })?;
    let payload_bytes = reader.get_ref().len() as u64;
    let layout = check_counts(&header, payload_bytes).map_err(|(el, rule)| ply(&el, rule))?;
    let mut vertices = Vec::new();
    let mut counts = Vec::new();
    let mut edges = Vec::new();
    for (name, def) in header.elements.iter() {
        let payload = |e: ply_rs_bw::parser::ParseError| {
            ply(
                name,
                format!("its values cannot be read: {}", short_message(&e)),
            )
        };
        if name == "vertex" {
            vertices = Parser::<Vertex>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map_err(payload)?;
        } else if Some(name) == layout.counts.as_ref().map(|c| &c.0) {
            counts = Parser::<Count>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map_err(payload)?;
        } else if Some(name) == layout.edges.as_ref() {
            edges = Parser::<Edge>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map_err(payload)?;
        } else {
            Parser::<Skip>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map_err(payload)?;
        }
    }
    let points = finite_points(&vertices).map_err(|rule| ply("vertex", rule))?;
    let (order, strand_points) = if let Some((element, segments)) = &layout.counts {
        let n = by_counts(&counts, *segments, points.len()).map_err(|rule| ply(element, rule))?;
        ((0..points.len() as u32).collect(), n)
    } else if layout.strand_index {
        by_strand_index(&vertices).map_err(|rule| ply("vertex", rule))?
    } else {
        let element = layout.edges.as_deref().unwrap_or("edge");
        by_edges(&edges, points.len()).map_err(|rule| ply(element, rule))?
    };
    Ok(StrandFile {
        points: order.iter().map(|&i| points[i as usize]).collect(),
        strand_points,
        thickness: None,
        colors: None,
    })
}

/// Checks the header of a `.ply` file of `file_len` bytes from its first bytes `head`: the
/// element counts against the caps (at most [`MAX_STRANDS`] strands in a strand element) and
/// the file's size, so a file that declares more than a groom may hold is refused before its
/// body is read. A header that does not end within `head` is left to [`parse_ply`].
pub fn check_ply_header(head: &[u8], file_len: u64, file: &str) -> Result<(), StrandFileError> {
    let mut reader = Reader::new(head);
    let header = match Parser::<Skip>::new().read_header(&mut reader) {
        Ok(header) => header,
        Err(_) if (head.len() as u64) < file_len => return Ok(()),
        Err(e) => {
            return Err(StrandFileError::PlyHeader {
                file: file.to_string(),
                rule: short_message(&e),
            });
        }
    };
    let header_bytes = (head.len() - reader.get_ref().len()) as u64;
    check_counts(&header, file_len.saturating_sub(header_bytes))
        .map(|_| ())
        .map_err(|(element, rule)| StrandFileError::Ply {
            file: file.to_string(),
            element,
            rule,
        })
}

/// The header's element counts against the caps and the `payload_bytes` after the header
/// (`check_sizes`), and the strand element's against [`MAX_STRANDS`]; then the layout.
/// Errors: (element, rule).
fn check_counts(header: &Header, payload_bytes: u64) -> Result<Layout, (String, String)> {
    check_sizes(header, payload_bytes)?;
    let layout = Layout::of(header)?;
    if let Some((name, _)) = &layout.counts
        && let Some(def) = header.elements.get(name)
        && def.count as u64 > MAX_STRANDS
    {
        return Err((
            name.clone(),
            format!(
                "the header declares {} strands, over the limit of {MAX_STRANDS} strands a groom may have",
                def.count
            ),
        ));
    }
    Ok(layout)
}

/// The PLY reader's message on one line: whole when short, else its line number and its
/// innermost part cut to 200 characters (an ASCII error quotes its line, which may be long).
fn short_message(e: &ply_rs_bw::parser::ParseError) -> String {
    let text = e
        .to_string()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    if text.chars().count() <= 300 {
        return text;
    }
    let line = e.line().map(|l| format!("Line {l}: ")).unwrap_or_default();
    let inner = text.rsplit("Error: ").next().unwrap_or(&text);
    format!("{line}{}", inner.chars().take(200).collect::<String>())
}

/// Which elements tell the strands (see the module doc for the order).
struct Layout {
    /// The strand element and whether its count is `segments` (one less than the vertices).
    counts: Option<(String, bool)>,
    /// Whether the vertices carry a strand index.
    strand_index: bool,
    /// The edge element.
    edges: Option<String>,
}

impl Layout {
    /// Reads the layout from the header, refusing a file without a `vertex` element with
    /// scalar `x`, `y`, `z` or without any of the three layouts. Errors: (element, rule).
    fn of(header: &Header) -> Result<Layout, (String, String)> {
        let Some(vertex) = header.elements.get("vertex") else {
            return Err((
                "vertex".into(),
                "the file has no `vertex` element: strand points are its x, y, z".into(),
            ));
        };
        for axis in ["x", "y", "z"] {
            scalar_property(vertex, axis)?.ok_or_else(|| {
                (
                    "vertex".to_string(),
                    format!("it has no property `{axis}`: every strand vertex needs x, y and z"),
                )
            })?;
        }
        let strand_index = first_scalar(vertex, &STRAND_INDEX_NAMES)?.is_some();
        let mut counts = None;
        for name in STRAND_ELEMENT_NAMES {
            let Some(def) = header.elements.get(name) else {
                continue;
            };
            if first_scalar(def, &VERTEX_COUNT_NAMES)?.is_some() {
                counts = Some((name.to_string(), false));
            } else if scalar_property(def, "segments")?.is_some() {
                counts = Some((name.to_string(), true));
            } else {
                return Err((
                    name.to_string(),
                    format!(
                        "a strand element needs a vertex count property ({} or segments)",
                        VERTEX_COUNT_NAMES.join(", ")
                    ),
                ));
            }
            break;
        }
        let mut edges = None;
        for name in EDGE_ELEMENT_NAMES {
            if let Some(def) = header.elements.get(name)
                && scalar_property(def, "vertex1")?.is_some()
                && scalar_property(def, "vertex2")?.is_some()
            {
                edges = Some(name.to_string());
                break;
            }
        }
        if counts.is_none() && !strand_index && edges.is_none() {
            return Err((
                "vertex".into(),
                format!(
                    "nothing says which vertices form a strand: expected a vertex property {}, \
                     a strand element ({}) with a vertex count, or an edge element ({}) with \
                     vertex1 and vertex2",
                    STRAND_INDEX_NAMES.join("/"),
                    STRAND_ELEMENT_NAMES.join("/"),
                    EDGE_ELEMENT_NAMES.join("/")
                ),
            ));
        }
        Ok(Layout {
            counts,
            strand_index,
            edges,
        })
    }
}

/// Whether `element` has the property `name`, refusing it as a list. Errors: (element, rule).
fn scalar_property(element: &ElementDef, name: &str) -> Result<Option<()>, (String, String)> {
    match element.properties.get(name).map(|p| &p.data_type) {
        None => Ok(None),
        Some(PropertyType::Scalar(_)) => Ok(Some(())),
        Some(PropertyType::List(..)) => Err((
            element.name.clone(),
            format!("property `{name}` is a list: it must be a single number"),
        )),
    }
}

/// The first of `names` that `element` has as a scalar property.
fn first_scalar(
    element: &ElementDef,
    names: &[&'static str],
) -> Result<Option<&'static str>, (String, String)> {
    for name in names {
        if scalar_property(element, name)?.is_some() {
            return Ok(Some(name));
        }
    }
    Ok(None)
}

/// Refuses an element count over [`MAX_ELEMENTS`] or a header whose elements need more bytes
/// than the `payload_bytes` after it (a lower bound: list lengths are not known yet).
fn check_sizes(header: &Header, payload_bytes: u64) -> Result<(), (String, String)> {
    let mut need = 0u64;
    for (name, def) in header.elements.iter() {
        if def.count > MAX_ELEMENTS {
            return Err((
                name.clone(),
                format!(
                    "the header declares {} of them, over the limit of {MAX_ELEMENTS}",
                    def.count
                ),
            ));
        }
        let each: u64 = def
            .properties
            .iter()
            .map(|(_, p)| match (&header.encoding, &p.data_type) {
                (Encoding::Ascii, _) => 2,
                (_, PropertyType::Scalar(s) | PropertyType::List(s, _)) => scalar_bytes(s),
            })
            .sum();
        need += each * def.count as u64;
        if need > payload_bytes {
            return Err((
                name.clone(),
                format!(
                    "the header declares {} of them, which with the elements before need at least {need} bytes; the file has {payload_bytes} after its header",
                    def.count
                ),
            ));
        }
    }
    Ok(())
}

fn scalar_bytes(s: &ScalarType) -> u64 {
    match s {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// The vertices' positions, refusing a coordinate that is not a finite 32-bit float.
fn finite_points(vertices: &[Vertex]) -> Result<Vec<Vec3>, String> {
    let mut points = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        let p = Vec3::from(v.p);
        if !p.is_finite() {
            return Err(format!(
                "vertex {i} is not finite ({p}): every coordinate must be a number within the 32-bit float range"
            ));
        }
        points.push(p);
    }
    Ok(points)
}

/// Points per strand from the strand element's counts (`segments`: one more), which must each
/// be at least 2 and add up to the `vertices`.
fn by_counts(counts: &[Count], segments: bool, vertices: usize) -> Result<Vec<u32>, String> {
    let mut out = Vec::with_capacity(counts.len());
    let mut total = 0u64;
    for (s, c) in counts.iter().enumerate() {
        let given = if segments { c.segments } else { c.vertices };
        let n = whole(given).map(|n| n + i64::from(segments));
        match n {
            Some(n) if (2..=i64::from(u32::MAX)).contains(&n) => {
                total += n as u64;
                out.push(n as u32);
            }
            _ => {
                return Err(format!(
                    "strand {s} has {}{} vertices: a strand needs at least 2 (a whole number)",
                    given,
                    if segments { " segments, so 1 more" } else { "" }
                ));
            }
        }
    }
    if total != vertices as u64 {
        return Err(format!(
            "the strands' vertex counts add up to {total}, but the `vertex` element has {vertices}"
        ));
    }
    Ok(out)
}

/// The vertex order (strand after strand) and points per strand from the per-vertex strand
/// index: a strand's vertices in file order, strands in the order of their first vertex.
fn by_strand_index(vertices: &[Vertex]) -> Result<(Vec<u32>, Vec<u32>), String> {
    let mut strand_of = HashMap::new();
    let mut members: Vec<Vec<u32>> = Vec::new();
    for (i, v) in vertices.iter().enumerate() {
        let Some(id) = whole(v.strand) else {
            return Err(format!(
                "vertex {i} has strand index {}: it must be a whole number",
                v.strand
            ));
        };
        let s = *strand_of.entry(id).or_insert_with(|| {
            members.push(Vec::new());
            members.len() - 1
        });
        members[s].push(i as u32);
    }
    if let Some(m) = members.iter().find(|m| m.len() < 2) {
        return Err(format!(
            "strand index {} has only vertex {}: a strand needs at least 2 vertices",
            vertices[m[0] as usize].strand, m[0]
        ));
    }
    let points = members.iter().map(|m| m.len() as u32).collect();
    Ok((members.concat(), points))
}

/// The vertex order and points per strand from edges chained into polylines (see the module
/// doc): every vertex on one or two edges, no loops.
fn by_edges(edges: &[Edge], vertices: usize) -> Result<(Vec<u32>, Vec<u32>), String> {
    const NONE: u32 = u32::MAX;
    let mut links = vec![[NONE; 2]; vertices];
    for (e, edge) in edges.iter().enumerate() {
        let ends = edge.0.map(whole);
        let (Some(a), Some(b)) = (ends[0], ends[1]) else {
            return Err(format!(
                "edge {e} joins {} and {}: vertex indices must be whole numbers",
                edge.0[0], edge.0[1]
            ));
        };
        if a == b || ![a, b].iter().all(|v| (0..vertices as i64).contains(v)) {
            return Err(format!(
                "edge {e} joins vertices {a} and {b}: they must be two different vertices of the {vertices}"
            ));
        }
        for (v, other) in [(a, b), (b, a)] {
            let slot = links[v as usize].iter().position(|&l| l == NONE);
            let Some(slot) = slot else {
                return Err(format!(
                    "vertex {v} is on 3 edges (edge {e} the third): strands do not branch"
                ));
            };
            links[v as usize][slot] = other as u32;
        }
    }
    let mut order = Vec::with_capacity(vertices);
    let mut points = Vec::new();
    let mut seen = vec![false; vertices];
    for root in 0..vertices {
        let [first, second] = links[root];
        if first == NONE {
            return Err(format!(
                "vertex {root} is on no edge: a strand needs at least 2 vertices"
            ));
        }
        if second != NONE || seen[root] {
            continue;
        }
        let start = order.len();
        let (mut prev, mut at) = (NONE, root as u32);
        while at != NONE && !seen[at as usize] {
            seen[at as usize] = true;
            order.push(at);
            let [l0, l1] = links[at as usize];
            let next = if l0 == prev { l1 } else { l0 };
            (prev, at) = (at, next);
        }
        points.push((order.len() - start) as u32);
    }
    if let Some(v) = seen.iter().position(|s| !s) {
        return Err(format!(
            "vertex {v} is on a closed loop of edges: a strand has a root and a tip"
        ));
    }
    Ok((order, points))
}

/// `v` as an integer if it is a whole number in the i64 range.
fn whole(v: f64) -> Option<i64> {
    (v.fract() == 0.0 && v.abs() < 9.0e18).then_some(v as i64)
}

/// A scalar property's value as f64 (exact for every PLY integer type); lists give `None`.
fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// A `vertex` element's record: its position (narrowed to f32, as [`StrandFile`] keeps it)
/// and its strand index (NaN when the file has none).
struct Vertex {
    p: [f32; 3],
    strand: f64,
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex {
            p: [0.0; 3],
            strand: f64::NAN,
        }
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let Some(v) = scalar(&property) else {
            return PropertyAccessResult::Ignored;
        };
        match name {
            "x" => self.p[0] = v as f32,
            "y" => self.p[1] = v as f32,
            "z" => self.p[2] = v as f32,
            n if STRAND_INDEX_NAMES.contains(&n) => self.strand = v,
            _ => return PropertyAccessResult::Ignored,
        }
        PropertyAccessResult::Set
    }
}

/// A strand element's record: its vertex count and its segments (NaN when absent).
struct Count {
    vertices: f64,
    segments: f64,
}

impl PropertyAccess for Count {
    fn new() -> Self {
        Count {
            vertices: f64::NAN,
            segments: f64::NAN,
        }
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        match scalar(&property) {
            Some(v) if VERTEX_COUNT_NAMES.contains(&name) => self.vertices = v,
            Some(v) if name == "segments" => self.segments = v,
            _ => return PropertyAccessResult::Ignored,
        }
        PropertyAccessResult::Set
    }
}

/// An edge element's record: its two vertex indices.
struct Edge([f64; 2]);

impl PropertyAccess for Edge {
    fn new() -> Self {
        Edge([f64::NAN; 2])
    }
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let slot = match name {
            "vertex1" => 0,
            "vertex2" => 1,
            _ => return PropertyAccessResult::Ignored,
        };
        match scalar(&property) {
            Some(v) => {
                self.0[slot] = v;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::Ignored,
        }
    }
}

/// An element read past.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}
