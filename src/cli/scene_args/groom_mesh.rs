//! A groom's own mesh: `.tfxmesh` files given in `--hairstyle` beside the groom's strands are
//! the surface the groom was authored on, drawn still under a groom kept as authored
//! (`--groom-as-authored`), in the groom's units (`wisp::input::tfxmesh`).

use crate::cli::AppError;
use std::path::Path;
use wisp::motion::{Character, Motion};

/// Whether a `--hairstyle` entry names a groom's mesh (by extension).
pub fn is_groom_mesh(arg: &str) -> bool {
    Path::new(arg)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("tfxmesh"))
}

/// The still motion of the groom's meshes `files`, scaled to metres by `unit_m` (the groom's
/// unit), as one character.
pub fn motion_of_meshes(files: &[&str], unit_m: f32) -> Result<Motion, AppError> {
    let (mut positions, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    for f in files {
        let mesh = wisp::input::tfxmesh::read_tfxmesh(Path::new(f)).map_err(AppError::input)?;
        let base = positions.len() as u32;
        positions.extend(mesh.positions.iter().map(|p| *p * unit_m));
        normals.extend(mesh.normals);
        triangles.extend(mesh.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    let character =
        Character::from_static_mesh(positions, normals, triangles).ok_or_else(|| {
            AppError::input(anyhow::anyhow!(
                "--hairstyle {}: the groom's meshes together have no triangle, more than a \
             character's caps of vertices or triangles, or coordinates that overflow at {unit_m} m \
             a unit",
                files.join(",")
            ))
        })?;
    Ok(Motion::still_with(character))
}
