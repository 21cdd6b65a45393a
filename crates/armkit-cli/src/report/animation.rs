//! The robot moving along the planned motion: the 3-D view
//! (`armkit_view`, links placed by armkit's FK) and, as its fallback where
//! the browser has no WebGL, a stick figure in an oblique view rendered as
//! inline SVG animated by a few lines of plain JavaScript.

use armkit::math::Pose;

/// The motion of a robot: for the 3-D view, the model and its
/// configurations (with the arm's base pose per frame when the base moves);
/// for the fallback, the stick figure's points per frame.
#[derive(Clone, Debug, Default)]
pub struct Animation {
    /// Time of each frame, s.
    pub times: Vec<f64>,
    /// Points of each frame: base first, end effector last (world frame, m).
    pub frames: Vec<Vec<[f64; 3]>>,
    /// The robot, when the animation was made from configurations.
    pub model: Option<armkit::Model>,
    /// Configuration of each frame (rad or m).
    pub configurations: Vec<Vec<f64>>,
    /// World pose of the arm's world frame at each frame (a moving base);
    /// empty: fixed.
    pub base_poses: Vec<Pose>,
    /// Per frame: inside a marked region (drawn red on the 3-D path).
    pub path_flags: Vec<bool>,
    /// Points marked in the 3-D view.
    pub markers: Vec<armkit_view::Marker>,
    /// A beam drawn bent in the 3-D view.
    pub beam: Option<armkit_view::BeamLine>,
    /// Shapes added to the arm's base link (a satellite's body), in the
    /// arm's world frame.
    pub base_shapes: Vec<armkit_view::Visual>,
}

/// Camera azimuth and elevation of the oblique view, rad.
const AZIMUTH: f64 = -0.9;
const ELEVATION: f64 = 0.45;
const WIDTH: f64 = 560.0;
const HEIGHT: f64 = 420.0;

/// Which frames the stick figure shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Playback {
    /// Every kept frame, played in a loop with a slider.
    Animated,
    /// The last frame only: the 3-D view's fallback image.
    LastFrame,
}

impl Animation {
    /// An animation from frame times and points.
    pub fn new(times: Vec<f64>, frames: Vec<Vec<[f64; 3]>>) -> Self {
        Animation {
            times,
            frames,
            ..Animation::default()
        }
    }

    /// The target position marked (green) in the 3-D view, world frame, m.
    pub fn with_target(mut self, target: &armkit::math::Vector3<f64>) -> Self {
        self.markers.push(armkit_view::Marker {
            at: [target.x, target.y, target.z],
            color: [0.1, 0.65, 0.2],
            label: "target".into(),
        });
        self
    }

    /// A free-floating base body drawn as a cube of its mass and mean
    /// principal inertia (`I = m s^2 / 6`) about its centre of mass, on the
    /// arm's base link (the base moves with it: see [`Self::place_frames`]).
    pub fn draw_base_body(&mut self, body: &armkit::space::BaseBody) {
        let inertia = body.inertia.trace() / 3.0;
        let side = if body.mass > 0.0 {
            (6.0 * inertia / body.mass).sqrt()
        } else {
            0.0
        };
        if !(side.is_finite() && side > 0.0) {
            return;
        }
        // The body's centre in the arm's world frame (the mount frame).
        let centre = body.mount.inverse().transform_point(&body.com);
        self.base_shapes.push(armkit_view::Visual {
            shape: armkit_view::Shape::Box {
                size: [side; 3],
                origin: Pose::from_translation(centre),
            },
            color: Some([0.75, 0.68, 0.3, 1.0]),
        });
    }

    /// Moves the arm's world frame to `worlds[k]` at frame `k` (a moving
    /// base): the stick figure's points and the 3-D view's links and path.
    pub fn place_frames(&mut self, worlds: &[Pose]) {
        for (frame, world) in self.frames.iter_mut().zip(worlds) {
            for p in frame.iter_mut() {
                let q = world.transform_point(&armkit::math::Vector3::from(*p));
                *p = [q.x, q.y, q.z];
            }
        }
        self.base_poses = worlds.to_vec();
    }

    /// The 3-D scene, links placed by armkit's FK (times the base pose of
    /// each frame when the base moves); `None` without a model.
    pub fn scene(&self) -> Option<Result<armkit_view::Scene, armkit::Error>> {
        let model = self.model.as_ref()?;
        Some(self.scene_of(model))
    }

    fn scene_of(&self, model: &armkit::Model) -> Result<armkit_view::Scene, armkit::Error> {
        let mut scene = armkit_view::chain_scene(model, &self.times, &self.configurations)?;
        if !self.base_poses.is_empty() {
            let picks = armkit_view::decimate(self.times.len().min(self.configurations.len()));
            for (frame, &k) in scene.poses.iter_mut().zip(&picks) {
                if let Some(world) = self.base_poses.get(k) {
                    for pose in frame.iter_mut() {
                        *pose = world * &*pose;
                    }
                }
            }
            for (p, world) in scene.path.iter_mut().zip(&self.base_poses) {
                let q = world.transform_point(&armkit::math::Vector3::from(*p));
                *p = [q.x, q.y, q.z];
            }
        }
        scene.markers = self.markers.clone();
        if self.path_flags.len() == scene.path.len() {
            scene.path_flags = self.path_flags.clone();
            // The middle of each flagged stretch marked red: a short region
            // (seed 004's is a tenth of a second) stays visible as a point.
            let mut k = 0;
            while k < scene.path_flags.len() {
                if !scene.path_flags[k] {
                    k += 1;
                    continue;
                }
                let start = k;
                while k < scene.path_flags.len() && scene.path_flags[k] {
                    k += 1;
                }
                scene.markers.push(armkit_view::Marker {
                    at: scene.path[(start + k - 1) / 2],
                    color: [0.85, 0.1, 0.1],
                    label: "inside the marked region".into(),
                });
            }
        }
        if let Some(base) = scene.links.first_mut() {
            let to_link = model.base().inverse();
            base.visuals
                .extend(self.base_shapes.iter().map(|v| match &v.shape {
                    armkit_view::Shape::Box { size, origin } => armkit_view::Visual {
                        shape: armkit_view::Shape::Box {
                            size: *size,
                            origin: to_link * *origin,
                        },
                        color: v.color,
                    },
                    _ => v.clone(),
                }));
        }
        // The beam's lines per frame, kept for the scene's frames.
        scene.beam = self.beam.as_ref().map(|beam| {
            let picks = armkit_view::decimate(beam.samples.len());
            armkit_view::BeamLine {
                magnification: beam.magnification,
                samples: picks.iter().map(|&k| beam.samples[k].clone()).collect(),
                straight: picks.iter().map(|&k| beam.straight[k].clone()).collect(),
            }
        });
        Ok(scene)
    }

    /// The robot `model` at each configuration: base origin, every joint
    /// frame's origin and the end effector, from forward kinematics.
    pub fn from_configurations(
        model: &armkit::Model,
        times: &[f64],
        configurations: &[Vec<f64>],
    ) -> Result<Self, armkit::Error> {
        let mut data = armkit::Data::new(model);
        let frames = configurations
            .iter()
            .map(|q| {
                let end = armkit::forward_kinematics(model, &mut data, q)?.translation;
                let base = model.base().translation;
                let mut points = vec![[base.x, base.y, base.z]];
                points.extend(data.joint_frames().iter().map(|f| {
                    let p = f.translation;
                    [p.x, p.y, p.z]
                }));
                points.push([end.x, end.y, end.z]);
                Ok(points)
            })
            .collect::<Result<Vec<_>, armkit::Error>>()?;
        Ok(Animation {
            model: Some(model.clone()),
            configurations: configurations.to_vec(),
            ..Animation::new(times.to_vec(), frames)
        })
    }

    /// The frames kept: those the 3-D view keeps ([`armkit_view::decimate`]).
    fn decimated(&self) -> Vec<usize> {
        armkit_view::decimate(self.frames.len().min(self.times.len()))
    }

    /// The oblique projection of a world point onto the screen (right, up).
    fn project(p: &[f64; 3]) -> (f64, f64) {
        let (sa, ca) = AZIMUTH.sin_cos();
        let (se, ce) = ELEVATION.sin_cos();
        let right = -p[0] * sa + p[1] * ca;
        let up = -p[0] * se * ca - p[1] * se * sa + p[2] * ce;
        (right, up)
    }

    /// The HTML block: an SVG canvas, play/pause, a time slider and the script.
    pub fn to_svg_html(&self) -> String {
        self.svg_html(Playback::Animated)
    }

    /// The stick figure at the last frame over the whole end-effector path:
    /// the 3-D view's fallback where the browser has no WebGL.
    pub fn to_still_svg_html(&self) -> String {
        self.svg_html(Playback::LastFrame)
    }

    fn svg_html(&self, playback: Playback) -> String {
        let picks = self.decimated();
        if picks.is_empty() {
            return String::new();
        }
        let projected: Vec<Vec<(f64, f64)>> = picks
            .iter()
            .map(|&k| self.frames[k].iter().map(Self::project).collect())
            .collect();
        let all = projected.iter().flatten();
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in all {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        let span = (x1 - x0).max(y1 - y0).max(1e-6);
        let scale = 0.9 * (WIDTH.min(HEIGHT)) / span;
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let to_screen = |(x, y): (f64, f64)| {
            (
                WIDTH / 2.0 + scale * (x - cx),
                HEIGHT / 2.0 - scale * (y - cy),
            )
        };
        // The path spans every kept frame; the figure shows `shown` of them.
        let shown = match playback {
            Playback::Animated => 0..picks.len(),
            Playback::LastFrame => picks.len() - 1..picks.len(),
        };
        let frames_json: Vec<String> = projected[shown.clone()]
            .iter()
            .map(|frame| {
                let pts: Vec<String> = frame
                    .iter()
                    .map(|&p| {
                        let (sx, sy) = to_screen(p);
                        format!("[{sx:.1},{sy:.1}]")
                    })
                    .collect();
                format!("[{}]", pts.join(","))
            })
            .collect();
        let times_json: Vec<String> = picks[shown.clone()]
            .iter()
            .map(|&k| format!("{:.3}", self.times[k]))
            .collect();
        let path: Vec<String> = projected
            .iter()
            .filter_map(|f| f.last())
            .map(|&p| {
                let (sx, sy) = to_screen(p);
                format!("{sx:.1},{sy:.1}")
            })
            .collect();
        let last = shown.len() - 1;
        format!(
            r##"<div class="animation-block">
<svg id="animation" viewBox="0 0 {WIDTH} {HEIGHT}" width="{WIDTH}" height="{HEIGHT}" role="img" aria-label="robot animation">
<rect width="100%" height="100%" fill="#fbfbfd" stroke="#ddd"/>
<polyline id="ee-path" points="{path}" fill="none" stroke="#e377c2" stroke-width="1.5" stroke-dasharray="4 3"/>
<polyline id="robot" points="" fill="none" stroke="#1f4e79" stroke-width="5" stroke-linejoin="round" stroke-linecap="round"/>
<g id="joints"></g>
<text id="anim-time" x="12" y="22" font-family="sans-serif" font-size="14">t = 0 s</text>
</svg>
<div><button id="anim-play" type="button">pause</button>
<input id="anim-slider" type="range" min="0" max="{last}" value="0" style="width:420px"></div>
<p class="caption">Stick figure (base, joint origins, end effector) in an oblique view; dashed: the end-effector path.</p>
</div>
<script>
(function() {{
  var frames = [{frames}];
  var times = [{times}];
  var robot = document.getElementById('robot');
  var joints = document.getElementById('joints');
  var label = document.getElementById('anim-time');
  var slider = document.getElementById('anim-slider');
  var button = document.getElementById('anim-play');
  var ns = 'http://www.w3.org/2000/svg';
  var circles = frames[0].map(function() {{
    var c = document.createElementNS(ns, 'circle');
    c.setAttribute('r', '4'); c.setAttribute('fill', '#ff7f0e'); joints.appendChild(c); return c;
  }});
  var k = 0, playing = true;
  function draw(i) {{
    var f = frames[i];
    robot.setAttribute('points', f.map(function(p) {{ return p[0] + ',' + p[1]; }}).join(' '));
    f.forEach(function(p, j) {{ circles[j].setAttribute('cx', p[0]); circles[j].setAttribute('cy', p[1]); }});
    label.textContent = 't = ' + times[i] + ' s';
    slider.value = i;
  }}
  function tick() {{ if (playing) {{ k = (k + 1) % frames.length; draw(k); }} }}
  slider.addEventListener('input', function() {{ k = parseInt(slider.value, 10); draw(k); }});
  button.addEventListener('click', function() {{ playing = !playing; button.textContent = playing ? 'pause' : 'play'; }});
  draw(0);
  setInterval(tick, 40);
}})();
</script>
"##,
            path = path.join(" "),
            frames = frames_json.join(","),
            times = times_json.join(","),
        )
    }
}
