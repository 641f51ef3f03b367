//! TressFX `.tfxmesh` files: the mesh a TressFX groom was authored on (its "collision mesh",
//! exported beside the `.tfx` strands by the TressFX Maya exporter), read so that a groom kept
//! as authored is drawn on its own surface.
//!
//! The format is text, one record a line, `#` starting a comment line:
//! ```text
//! numOfBones B
//! <B lines: index name>
//! numOfVertices V
//! <V lines: index  x y z  nx ny nz  j0 j1 j2 j3  w0 w1 w2 w3>
//! numOfTriangles T
//! <T lines: index  a b c>
//! ```
//! Positions are in the groom's units and frame. The bone names and weights bind the mesh to
//! the game's skeleton, which the file does not carry, so the mesh is read as it stands (the
//! bones are counted, not used). Every index must be in order and every vertex index of a
//! triangle in range; counts are checked against the file's size and the caps before anything
//! is allocated for them.

use super::{ReadError, read_capped};
use glam::Vec3;
use std::path::Path;

/// Largest `.tfxmesh` file read, bytes.
pub const MAX_TFXMESH_BYTES: u64 = 512 << 20;
/// Most vertices a `.tfxmesh` may have (a character's cap, `motion::skin::MAX_VERTICES`).
pub const MAX_TFXMESH_VERTICES: usize = 1 << 20;
/// Most triangles a `.tfxmesh` may have (`motion::skin::MAX_TRIANGLES`).
pub const MAX_TFXMESH_TRIANGLES: usize = 2 << 20;
/// Fewest bytes a vertex line can take ("0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n"), for the size check.
const MIN_VERTEX_LINE_BYTES: u64 = 30;
/// Fewest bytes a triangle line can take ("0 0 0 0\n").
const MIN_TRIANGLE_LINE_BYTES: u64 = 8;

/// A groom's mesh: positions and unit normals (file units and frame), triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TfxMesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    /// Bones the file names (not used: see the module doc).
    pub bones: usize,
}

/// Why a `.tfxmesh` file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TfxMeshError {
    #[error("{file}: {error}")]
    Io { file: String, error: ReadError },
    #[error("{file}: line {line}: {rule}")]
    Malformed {
        file: String,
        line: usize,
        rule: String,
    },
}

/// Reads the `.tfxmesh` at `path`.
pub fn read_tfxmesh(path: &Path) -> Result<TfxMesh, TfxMeshError> {
    let file = super::printable(&path.display().to_string());
    let bytes = read_capped(path, MAX_TFXMESH_BYTES, "a TressFX mesh").map_err(|error| {
        TfxMeshError::Io {
            file: file.clone(),
            error,
        }
    })?;
    parse_tfxmesh(&bytes, &file)
}

/// Parses the bytes of a `.tfxmesh`; `file` names it in errors.
pub fn parse_tfxmesh(bytes: &[u8], file: &str) -> Result<TfxMesh, TfxMeshError> {
    let text = std::str::from_utf8(bytes).map_err(|e| TfxMeshError::Malformed {
        file: file.to_string(),
        line: 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|b| **b == b'\n')
            .count(),
        rule: "not UTF-8 text (a .tfxmesh is text)".to_string(),
    })?;
    let mut lines = Lines {
        inner: text.lines().enumerate(),
        file,
    };
    let len = bytes.len() as u64;
    let bones = lines.count("numOfBones", len / 2, usize::MAX)?;
    for k in 0..bones {
        let (line, fields) = lines.record()?;
        lines.index_is(line, &fields, k, 2)?;
    }
    let vertices = lines.count(
        "numOfVertices",
        len / MIN_VERTEX_LINE_BYTES,
        MAX_TFXMESH_VERTICES,
    )?;
    let mut mesh = TfxMesh {
        positions: Vec::with_capacity(vertices),
        normals: Vec::with_capacity(vertices),
        triangles: Vec::new(),
        bones,
    };
    for k in 0..vertices {
        let (line, fields) = lines.record()?;
        lines.index_is(line, &fields, k, 15)?;
        let v: Vec<f32> = fields[1..7]
            .iter()
            .map(|f| lines.number(line, f))
            .collect::<Result<_, _>>()?;
        mesh.positions.push(Vec3::new(v[0], v[1], v[2]));
        mesh.normals
            .push(Vec3::new(v[3], v[4], v[5]).normalize_or(Vec3::Y));
    }
    let triangles = lines.count(
        "numOfTriangles",
        len / MIN_TRIANGLE_LINE_BYTES,
        MAX_TFXMESH_TRIANGLES,
    )?;
    mesh.triangles.reserve_exact(triangles);
    for k in 0..triangles {
        let (line, fields) = lines.record()?;
        lines.index_is(line, &fields, k, 4)?;
        let mut t = [0u32; 3];
        for (c, f) in t.iter_mut().zip(&fields[1..4]) {
            *c = f
                .parse::<u32>()
                .ok()
                .filter(|i| (*i as usize) < vertices)
                .ok_or_else(|| {
                    lines.bad(
                        line,
                        format!("vertex index {f} is not one of the {vertices} vertices"),
                    )
                })?;
        }
        mesh.triangles.push(t);
    }
    Ok(mesh)
}

/// The file's lines with their numbers, comments and blank lines skipped.
struct Lines<'a, I> {
    inner: I,
    file: &'a str,
}

impl<'a, I: Iterator<Item = (usize, &'a str)>> Lines<'a, I> {
    fn bad(&self, line: usize, rule: String) -> TfxMeshError {
        TfxMeshError::Malformed {
            file: self.file.to_string(),
            line,
            rule,
        }
    }

    /// The next record's line number (from 1) and fields.
    fn record(&mut self) -> Result<(usize, Vec<&'a str>), TfxMeshError> {
        for (i, l) in self.inner.by_ref() {
            let l = l.trim();
            if !(l.is_empty() || l.starts_with('#')) {
                return Ok((i + 1, l.split_whitespace().collect()));
            }
        }
        Err(TfxMeshError::Malformed {
            file: self.file.to_string(),
            line: 0,
            rule: "the file ends before its last record (a count promises more lines)".into(),
        })
    }

    /// The count of a `key N` line, at most `fits` (what the file's size can hold) and `cap`.
    fn count(&mut self, key: &str, fits: u64, cap: usize) -> Result<usize, TfxMeshError> {
        let (line, fields) = self.record()?;
        if fields.len() != 2 || fields[0] != key {
            return Err(self.bad(
                line,
                format!("expected `{key} N`, found `{}`", fields.join(" ")),
            ));
        }
        let n: u64 = fields[1]
            .parse()
            .map_err(|_| self.bad(line, format!("{key} `{}` is not a count", fields[1])))?;
        if n > fits || n > cap as u64 {
            return Err(self.bad(
                line,
                format!("{key} {n} is more than the file's size can hold or the cap of {cap}"),
            ));
        }
        Ok(n as usize)
    }

    /// Checks a record has `len` fields, the first being the index `k`.
    fn index_is(
        &self,
        line: usize,
        fields: &[&str],
        k: usize,
        len: usize,
    ) -> Result<(), TfxMeshError> {
        if fields.len() != len {
            return Err(self.bad(
                line,
                format!("{} fields where {len} are expected", fields.len()),
            ));
        }
        if fields[0].parse::<usize>().ok() != Some(k) {
            return Err(self.bad(line, format!("index `{}` where {k} is expected", fields[0])));
        }
        Ok(())
    }

    /// A finite number.
    fn number(&self, line: usize, f: &str) -> Result<f32, TfxMeshError> {
        f.parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| self.bad(line, format!("`{f}` is not a finite number")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE_TRIANGLE: &str = "# exported\nnumOfBones 1\n# bone index, bone name\n0 head_JNT\n\
        numOfVertices 3\n# vertex ...\n0 0 0 0 0 0 2 0 0 0 0 1 0 0 0\n\
        1 1 0 0 0 0 1 0 0 0 0 1 0 0 0\n2 0 1 0 0 0 1 0 0 0 0 1 0 0 0\n\
        numOfTriangles 1\n# triangle index, ...\n0 0 1 2\n";

    #[test]
    fn a_mesh_is_read_with_unit_normals() {
        let m = parse_tfxmesh(ONE_TRIANGLE.as_bytes(), "m.tfxmesh").unwrap();
        assert_eq!(m.bones, 1);
        assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert_eq!(m.normals, vec![Vec3::Z; 3]);
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn broken_files_name_the_line_and_rule() {
        let cases = [
            (
                ONE_TRIANGLE.replace("0 0 1 2\n", "0 0 1 3\n"),
                "line 12",
                "vertex index 3",
            ),
            (
                ONE_TRIANGLE.replace("numOfVertices 3", "numOfVertices 9999999"),
                "line 5",
                "cap",
            ),
            (
                ONE_TRIANGLE.replace("1 1 0 0", "1 nan 0 0"),
                "line 8",
                "not a finite number",
            ),
            (
                ONE_TRIANGLE.replace("2 0 1 0", "5 0 1 0"),
                "line 9",
                "index `5` where 2",
            ),
            (
                ONE_TRIANGLE.replace(
                    "numOfTriangles 1\n# triangle index, ...\n0 0 1 2\n",
                    "numOfTriangles 1\n",
                ),
                "line 0",
                "ends before",
            ),
            (
                ONE_TRIANGLE.replace("numOfBones", "bones"),
                "line 2",
                "expected `numOfBones N`",
            ),
        ];
        for (text, line, rule) in cases {
            let e = parse_tfxmesh(text.as_bytes(), "m.tfxmesh")
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("m.tfxmesh") && e.contains(line) && e.contains(rule),
                "{e}"
            );
        }
    }
}
