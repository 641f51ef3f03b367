//! The motion's flags: which clip of which glTF file the head and body follow, how the
//! hairstyle's head is fitted to the character's, and how fast it plays (`wisp::motion`).

use crate::cli::{AppError, parse_point, parse_positive_f32, parse_speed};
use glam::Vec3;
use std::path::PathBuf;
use wisp::motion::{Fit, JointRef, Motion, MotionError, MotionOptions};

#[derive(clap::Args, Debug, Clone)]
#[command(next_help_heading = "Motion")]
pub struct MotionArgs {
    /// Motion: a glTF 2.0 file, .glb or .gltf [default: the embedded dance]
    #[arg(long, value_name = "FILE")]
    pub animation: Option<PathBuf>,
    /// Animation clip [default: "Dance" if present, else the first]
    #[arg(long, value_name = "NAME")]
    pub clip: Option<String>,
    /// Head joint, node name or index [default: one with "head" in its name, else the
    /// topmost joint]
    #[arg(long, value_name = "JOINT")]
    pub head_joint: Option<String>,
    /// Keep the file's axes when its model lies along Z or X instead of standing along +Y
    /// [default: such a model is turned upright]
    #[arg(long)]
    pub keep_axes: bool,
    /// Head fit: size over the hairstyle's 0.09 m head; with --head-offset
    #[arg(long, value_name = "S", value_parser = parse_positive_f32, requires = "head_offset")]
    pub head_scale: Option<f32>,
    /// Head fit: centre in the joint's frame, model metres; with --head-scale
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true, requires = "head_scale")]
    pub head_offset: Option<Vec3>,
    /// Playback speed, 1 = real time, in (0, 1000]
    #[arg(long, value_name = "X", default_value_t = 1.0, value_parser = parse_speed, allow_hyphen_values = true)]
    pub speed: f32,
    /// No motion: the character stands in the clip's first pose, its head at the origin (with
    /// --no-solids, the head alone)
    #[arg(long)]
    pub still: bool,
}

impl MotionArgs {
    /// The motion: the clip of the `--animation` file or the embedded dance, held in its first
    /// pose with `--still` ([`Motion::held_still`]). `hair_alone` (no solids drawn) with
    /// `--still` gives the head alone at the origin ([`Motion::still`]): nothing of a body
    /// would be seen, and hair hanging free from a bare head is the setup the comparisons with
    /// path tracers (`tools/reference`) export.
    pub fn load(&self, hair_alone: bool) -> Result<Motion, AppError> {
        if self.still && hair_alone {
            return Ok(Motion::still(glam::Affine3A::IDENTITY));
        }
        let motion = self.load_clip()?;
        Ok(if self.still {
            motion.held_still()
        } else {
            motion
        })
    }

    /// The motion of a groom kept as authored: the `--animation` file's character as the
    /// file has it (in its own metres, no head fit) with no body colliders, since the groom
    /// was authored around the character's own surface, which capsules would only
    /// approximate; without `--animation`, nothing (the roots stay where the file has them).
    pub fn load_for_authored_groom(&self) -> Result<Motion, AppError> {
        if self.animation.is_none() {
            return Ok(Motion::still(glam::Affine3A::IDENTITY));
        }
        let motion = self.load_clip_with(|opts| {
            opts.fit = Some(Fit::IDENTITY);
            opts.body_spheres = Some(Vec::new());
            opts.body_capsules = false;
        })?;
        Ok(if self.still {
            motion.held_still()
        } else {
            motion
        })
    }

    /// The clip of the `--animation` file, or the embedded dance.
    fn load_clip(&self) -> Result<Motion, AppError> {
        self.load_clip_with(|_| {})
    }

    /// [`Self::load_clip`] with the options the flags give changed by `adjust`.
    fn load_clip_with(&self, adjust: impl FnOnce(&mut MotionOptions)) -> Result<Motion, AppError> {
        let mut opts = MotionOptions {
            clip: self.clip.clone(),
            head_joint: self
                .head_joint
                .as_deref()
                .map(|s| match s.parse::<usize>() {
                    Ok(i) => JointRef::Index(i),
                    Err(_) => JointRef::Name(s.to_string()),
                }),
            speed: self.speed,
            keep_axes: self.keep_axes,
            fit: self
                .head_scale
                .zip(self.head_offset)
                .map(|(scale, offset_m)| Fit { scale, offset_m }),
            ..MotionOptions::default()
        };
        adjust(&mut opts);
        match &self.animation {
            Some(path) => {
                let motion = Motion::load(path, &opts).map_err(|e| self.motion_error(e))?;
                // Say what was chosen: a rig's clips and joints are many, and a wrong head or
                // clip shows only as hair that looks wrong.
                eprintln!(
                    "wisp: {}: clip \"{}\" ({:.1} s), head joint \"{}\" (node {}{}); --clip and \
                     --head-joint choose others",
                    path.display(),
                    motion.clip_name(),
                    motion.duration_s(),
                    motion.head_joint().1,
                    motion.head_joint().0,
                    if motion.head_is_topmost() {
                        ", the topmost joint: none is named like \"head\""
                    } else {
                        ""
                    }
                );
                if motion.file_up() != Vec3::Y {
                    eprintln!(
                        "wisp: {}: the model stands along {} in the file, not glTF's +Y (its \
                         neck-to-head direction): turned upright; --keep-axes keeps the file's axes",
                        path.display(),
                        axis_name(motion.file_up())
                    );
                }
                if let Some(n) = motion.character().map(|c| c.unread_textures)
                    && n > 0
                {
                    eprintln!(
                        "wisp: warning: {}: {n} base colour texture(s) in a format wisp does not \
                         read (it reads PNG and grey or RGB JPEG): their materials keep their \
                         colour factor",
                        path.display()
                    );
                }
                Ok(motion)
            }
            None => {
                if self.clip.is_some() || self.head_joint.is_some() {
                    return Err(AppError::input(anyhow::anyhow!(
                        "--clip and --head-joint need --animation FILE (the embedded dance has one clip)"
                    )));
                }
                wisp::motion::dance::try_dance(&opts).map_err(AppError::other)
            }
        }
    }

    /// A motion error, with the flag that fixes it when there is one.
    fn motion_error(&self, e: MotionError) -> AppError {
        let hint = match &e {
            MotionError::UnknownJoint { role, .. } if role == "head joint" => {
                if self.head_joint.is_none() {
                    "; choose the head with --head-joint NAME|INDEX"
                } else {
                    "; give one of these to --head-joint"
                }
            }
            MotionError::UnknownClip { .. } => "; give one of these to --clip",
            _ => "",
        };
        AppError::input(anyhow::anyhow!("{e}{hint}"))
    }

    /// The file the motion comes from, for messages: its path, or "the embedded dance".
    pub fn source(&self) -> String {
        self.animation
            .as_ref()
            .map_or("the embedded dance".to_string(), |p| {
                p.display().to_string()
            })
    }

    /// What the motion flags chose, for a simulation cache's header and messages.
    /// `hair_alone` as [`Self::load`] took it.
    pub fn label(&self, motion: &Motion, hair_alone: bool) -> String {
        if self.still && hair_alone {
            return "--still (no motion)".to_string();
        }
        let clip = format!(
            "clip \"{}\" of {}, head joint \"{}\"{}",
            motion.clip_name(),
            self.source(),
            motion.head_joint().1,
            if self.keep_axes {
                ", the file's axes kept"
            } else {
                ""
            }
        );
        if self.still {
            format!("--still: the first pose of {clip}")
        } else {
            format!("{clip}, speed {}", motion.speed())
        }
    }
}

/// "+Z", "-X", … for a world axis.
fn axis_name(a: Vec3) -> String {
    let (sign, name) = if a.x.abs() > 0.5 {
        (a.x, "X")
    } else if a.y.abs() > 0.5 {
        (a.y, "Y")
    } else {
        (a.z, "Z")
    };
    format!("{}{name}", if sign < 0.0 { "-" } else { "+" })
}
