//! The load's last check: a clip whose head or colliders leave the range where f32 positions
//! resolve the collision margin is refused ([`MAX_POSE_DISTANCE_M`]).
//!
//! The pose is checked at every key time of the evaluated nodes and at 1,001 uniform times
//! over the clip, at most [`REACH_SAMPLES`] poses in all (a clip with more keys is checked at
//! an even stride of them), so a file of millions of keys costs no more to check than an
//! ordinary clip.

use glam::Vec3;

use super::playback::Motion;
use super::pose::Pose;

/// Farthest a head or body collider may be from the world origin, pose metres. Positions are
/// f32: at 10 km their spacing is 1 mm, the collision margin, and beyond it the hair simulation
/// and the camera lose the hair (keyframes of 1e30 give blank frames).
pub const MAX_POSE_DISTANCE_M: f32 = 10_000.0;

/// Most clip times [`Motion`] loading samples to check [`MAX_POSE_DISTANCE_M`].
pub(super) const REACH_SAMPLES: usize = 10_000;

impl Motion {
    /// Checks that the head and the colliders stay finite and within [`MAX_POSE_DISTANCE_M`]
    /// of the origin over the clip: at every key time of the evaluated nodes and at uniform
    /// times between (at most [`REACH_SAMPLES`] poses in all).
    pub(crate) fn check_reach(&self) -> Result<(), String> {
        let mut pose = Pose::default();
        for clip_t in self.reach_times() {
            self.pose_at_clip_time(clip_t, &mut pose);
            check_pose_reach(&pose, clip_t)?;
        }
        Ok(())
    }

    /// The clip times [`Motion::check_reach`] samples: the key times of the evaluated nodes'
    /// tracks (strided down when there are too many), then 1,001 uniform times over the clip.
    fn reach_times(&self) -> Vec<f32> {
        let mut times: Vec<f32> = self
            .nodes
            .iter()
            .flat_map(|n| [&n.translation, &n.rotation, &n.scale])
            .flatten()
            .flat_map(|t| t.times_s().iter().copied())
            .collect();
        let uniform = 1000;
        if times.len() > REACH_SAMPLES - uniform - 1 {
            let stride = times.len().div_ceil(REACH_SAMPLES - uniform - 1);
            times = times.into_iter().step_by(stride).collect();
        }
        times.extend(
            (0..=uniform).map(|i| self.start_s + self.duration_s * (i as f32 / uniform as f32)),
        );
        times
    }
}

/// Refuses `pose` (at clip time `clip_t`) when its head or a collider is not finite or lies
/// farther than [`MAX_POSE_DISTANCE_M`] from the origin.
fn check_pose_reach(pose: &Pose, clip_t: f32) -> Result<(), String> {
    let head = Vec3::from(pose.head.translation);
    let far = |p: Vec3| !(p.is_finite() && p.length() <= MAX_POSE_DISTANCE_M);
    if far(head) || !pose.head.matrix3.is_finite() {
        return Err(format!(
            "at clip time {clip_t} s the head is at {head} (pose metres, after the fit); \
             it must stay finite and within {MAX_POSE_DISTANCE_M} m of the origin, where \
             f32 positions still resolve the 1 mm collision margin"
        ));
    }
    if let Some(c) = pose.capsules.iter().find(|c| far(c.a) || far(c.b)) {
        return Err(format!(
            "at clip time {clip_t} s a body capsule reaches {} (pose metres, after the \
             fit); colliders must stay finite and within {MAX_POSE_DISTANCE_M} m of \
             the origin",
            if far(c.a) { c.a } else { c.b }
        ));
    }
    if let Some(s) = pose
        .spheres
        .iter()
        .find(|s| far(s.center) || !s.radius_m.is_finite())
    {
        return Err(format!(
            "at clip time {clip_t} s a body collider is at {} (pose metres, after the \
             fit); colliders must stay finite and within {MAX_POSE_DISTANCE_M} m of \
             the origin",
            s.center
        ));
    }
    Ok(())
}
