//! The glTF JSON document, parsed and validated by the gltf crate after two checks of our own.
//!
//! - Size: at most [`MAX_JSON_CONTAINERS`] objects and arrays, counted on the text before it
//!   is parsed (each becomes a struct of up to a few hundred bytes).
//! - Indices the crate trusts or never checks: it indexes `accessors` with a primitive's
//!   POSITION attribute before validating it, and it does not check an animation channel's
//!   `target` (an out-of-range node or an unknown `path`), which its accessors then unwrap:
//!   either panics unless refused here first.
//!
//! The crate's own problems are reported in one short sentence, at most a few listed.

use gltf::json::validation::Checked;

use super::MAX_JSON_CONTAINERS;
use crate::motion::error::{MotionError, invalid, short_list};

/// The validated document of the JSON text `json`.
pub(super) fn document(json: &[u8], file: &str) -> Result<gltf::Document, MotionError> {
    let containers = count_containers(json);
    if containers > MAX_JSON_CONTAINERS {
        return Err(invalid(
            file,
            format!(
                "the JSON has {containers} objects and arrays, more than the {MAX_JSON_CONTAINERS} accepted"
            ),
        ));
    }
    let root =
        gltf::json::Root::from_slice(json).map_err(|e| invalid(file, format!("JSON: {e}")))?;
    check_trusted_indices(&root).map_err(|reason| invalid(file, reason))?;
    gltf::Document::from_json(root).map_err(|e| invalid(file, describe(e)))
}

/// Objects and arrays in a JSON text, counted without parsing (string contents skipped).
fn count_containers(json: &[u8]) -> usize {
    let (mut n, mut in_string, mut escaped) = (0usize, false, false);
    for &b in json {
        if in_string {
            if escaped {
                escaped = false;
            } else if b == b'\\' {
                escaped = true;
            } else if b == b'"' {
                in_string = false;
            }
        } else {
            match b {
                b'"' => in_string = true,
                b'{' | b'[' => n += 1,
                _ => {}
            }
        }
    }
    n
}

/// The gltf crate's error as one short sentence (its own Display lists every problem and
/// starts with "invalid glTF:", which our message already says).
fn describe(e: gltf::Error) -> String {
    match e {
        gltf::Error::Validation(list) => {
            let n = list.len();
            let items = list.into_iter().map(|(path, err)| format!("{path}: {err}"));
            format!(
                "{n} problem{}: {}",
                if n == 1 { "" } else { "s" },
                short_list(items, "; ")
            )
        }
        gltf::Error::Deserialize(e) => format!("JSON: {e}"),
        other => other.to_string(),
    }
}

/// Indices the gltf crate's validation trusts (it indexes `accessors` with a primitive's
/// POSITION attribute before checking it, and panics) or never checks (each animation channel's
/// target node and path, which its accessors then unwrap). Run before the crate's validation.
fn check_trusted_indices(root: &gltf::json::Root) -> Result<(), String> {
    let mut problems = Vec::new();
    let position = Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(acc) = prim.attributes.get(&position)
                && acc.value() >= root.accessors.len()
            {
                problems.push(format!(
                    "meshes[{m}].primitives[{p}].attributes.POSITION: accessor {} is out of range (the file has {} accessors)",
                    acc.value(),
                    root.accessors.len()
                ));
            }
        }
    }
    for (a, anim) in root.animations.iter().enumerate() {
        for (c, ch) in anim.channels.iter().enumerate() {
            let node = ch.target.node.value();
            if node >= root.nodes.len() {
                problems.push(format!(
                    "animations[{a}].channels[{c}].target.node: {node} is out of range (the file has {} nodes)",
                    root.nodes.len()
                ));
            }
            if matches!(ch.target.path, Checked::Invalid) {
                problems.push(format!(
                    "animations[{a}].channels[{c}].target.path: not one of \"translation\", \"rotation\", \"scale\", \"weights\""
                ));
            }
        }
    }
    if problems.is_empty() {
        return Ok(());
    }
    let n = problems.len();
    Err(format!(
        "{n} problem{}: {}",
        if n == 1 { "" } else { "s" },
        short_list(problems.into_iter(), "; ")
    ))
}
