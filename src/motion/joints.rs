//! Finding a joint in the node hierarchy: a [`JointRef`] asked for by name or node index, or
//! the default head joint.
//!
//! Names match exactly first, then case-insensitively, and skin joints win over other nodes
//! of the same name (a mesh or helper node may share its bone's name). The default head is a
//! joint named "head", else the shortest joint name containing "head" but neither "end" nor
//! "top": rigs add leaf bones such as `Head_end` or `HeadTop_End` above the skull, which are
//! not where the head turns.

use super::error::MotionError;
use super::options::JointRef;
use super::skeleton::Skeleton;

/// Resolves a [`JointRef`]: exact name, then case-insensitive; joints before other nodes.
pub(super) fn resolve_joint(
    skel: &Skeleton,
    r: &JointRef,
    file: &str,
    role: &str,
) -> Result<usize, MotionError> {
    let found = match r {
        JointRef::Index(i) => (*i < skel.names.len()).then_some(*i),
        JointRef::Name(name) => {
            let by = |pred: &dyn Fn(usize) -> bool| (0..skel.names.len()).find(|&i| pred(i));
            by(&|i| skel.is_joint[i] && skel.names[i] == *name)
                .or_else(|| by(&|i| skel.names[i] == *name))
                .or_else(|| by(&|i| skel.is_joint[i] && skel.names[i].eq_ignore_ascii_case(name)))
                .or_else(|| by(&|i| skel.names[i].eq_ignore_ascii_case(name)))
        }
    };
    found.ok_or_else(|| MotionError::UnknownJoint {
        file: file.to_string(),
        role: role.to_string(),
        requested: match r {
            JointRef::Index(i) => format!(
                "with node index {i} (the file has {} nodes)",
                skel.names.len()
            ),
            JointRef::Name(n) => format!("named {n:?}"),
        },
        available: skel.joint_list(),
    })
}

/// Default head: a joint named "head" (any case), else the shortest joint name containing
/// "head" but neither "end" nor "top" (skips `Head_end`, `HeadTop_End`).
pub(super) fn default_head(skel: &Skeleton, file: &str) -> Result<usize, MotionError> {
    let lower: Vec<String> = skel.names.iter().map(|n| n.to_lowercase()).collect();
    let joints = || (0..skel.names.len()).filter(|&i| skel.is_joint[i]);
    joints()
        .find(|&i| lower[i] == "head")
        .or_else(|| {
            joints()
                .filter(|&i| {
                    lower[i].contains("head")
                        && !lower[i].contains("end")
                        && !lower[i].contains("top")
                })
                .min_by_key(|&i| (lower[i].len(), i))
        })
        .ok_or_else(|| MotionError::UnknownJoint {
            file: file.to_string(),
            role: "head joint".to_string(),
            requested: "named like \"head\"".to_string(),
            available: skel.joint_list(),
        })
}
