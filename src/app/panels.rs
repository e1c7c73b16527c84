//! The egui panels: HUD (always shown), and the tuning side panel: scene
//! and run controls, attention, personality, gains with plots and step
//! response, emotions and Action Units.

use eframe::egui::{self, RichText};
use egui_plot::{Legend, Line, Plot, PlotPoints};

use shisen::physics::body::Group;
use shisen::sim::timeline::{Action, Event};
use shisen_face::tables::{ActionUnit, Emotion};
use shisen_face::timing::{Pattern, Speed};

use super::session::Session;
use super::tuning::{StepResponse, step_response};

/// UI state of the panels that is not simulation state.
pub struct PanelState {
    /// Scene file field.
    pub scene_path: String,
    /// Recording output field.
    pub record_path: String,
    /// Trace output field.
    pub trace_path: String,
    /// Gains file field.
    pub gains_path: String,
    /// Last status or error message (errors in red).
    pub status: Option<(String, bool)>,
    /// Sections open at start: `scene`, `attention`, `personality`, `gains`, `face`.
    pub open: Vec<String>,
    emotion: Emotion,
    intensity: f32,
    speed: Speed,
    step: Option<StepResponse>,
}

impl Default for PanelState {
    fn default() -> Self {
        PanelState {
            scene_path: "scenes/look_sequence.ron".into(),
            record_path: "session.ron".into(),
            trace_path: "trace.csv".into(),
            gains_path: "scenes/gains/default.ron".into(),
            status: None,
            open: vec!["scene".into(), "attention".into()],
            emotion: Emotion::Happiness,
            intensity: 0.8,
            speed: Speed::Typical,
            step: None,
        }
    }
}

impl PanelState {
    /// Open these sections at start (`gains` also shows a neck step response).
    pub fn open_sections(&mut self, sections: &[String], gains: &shisen::physics::control::Gains) {
        self.open = sections.to_vec();
        if self.open.iter().any(|s| s == "gains") {
            self.step = Some(step_response(gains, Group::Neck));
        }
    }

    fn is_open(&self, section: &str) -> bool {
        self.open.iter().any(|s| s == section)
    }

    /// Show a message (an error if `error`).
    pub fn say(&mut self, msg: impl Into<String>, error: bool) {
        let msg = msg.into();
        if error {
            tracing::warn!("{msg}");
        }
        self.status = Some((msg, error));
    }
}

/// The tuning side panel.
pub fn tuning(
    ui: &mut egui::Ui,
    s: &mut Session,
    st: &mut PanelState,
    view: &mut super::view3d::Viewport,
) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        if let Some((msg, error)) = &st.status {
            let colour = if *error {
                egui::Color32::LIGHT_RED
            } else {
                egui::Color32::LIGHT_GREEN
            };
            ui.label(RichText::new(msg).color(colour));
        }
        let header =
            |name: &str, key: &str| egui::CollapsingHeader::new(name).default_open(st.is_open(key));
        let (scene_h, attention_h, personality_h, gains_h, face_h) = (
            header("Scene and run", "scene"),
            header("Attention", "attention"),
            header("Personality", "personality"),
            header("PD gains", "gains"),
            header("Face", "face"),
        );
        let recording = s.recorder.is_some();
        scene_h.show(ui, |ui| run(ui, s, st, view));
        attention_h.show(ui, |ui| attention(ui, s));
        personality_h.show(ui, |ui| {
            ui.add_enabled_ui(!recording, |ui| personality(ui, s));
        });
        gains_h.show(ui, |ui| {
            ui.add_enabled_ui(!recording, |ui| gains(ui, s, st));
        });
        face_h.show(ui, |ui| face(ui, s, st));
    });
}

fn run(
    ui: &mut egui::Ui,
    s: &mut Session,
    st: &mut PanelState,
    view: &mut super::view3d::Viewport,
) {
    ui.label(format!("scene: {}", s.loaded.scene.name));
    ui.horizontal(|ui| {
        ui.text_edit_singleline(&mut st.scene_path);
        if ui.button("Open").clicked() {
            let path = std::path::PathBuf::from(&st.scene_path);
            match s.open(&path) {
                Ok(()) => st.say(format!("opened {}", path.display()), false),
                Err(e) => st.say(format!("{e:#}"), true),
            }
        }
    });
    ui.horizontal(|ui| {
        if ui.button("Restart").clicked() {
            s.restart();
        }
        let label = if s.clock.paused { "Resume" } else { "Pause" };
        if ui.button(label).clicked() {
            s.clock.paused = !s.clock.paused;
        }
        if ui
            .add_enabled(s.clock.paused, egui::Button::new("Step"))
            .clicked()
        {
            s.step();
        }
        ui.checkbox(&mut s.clock.slow, "slow motion");
    });
    ui.horizontal(|ui| {
        ui.text_edit_singleline(&mut st.record_path);
        if s.recorder.is_none() {
            if ui
                .button("Record")
                .on_hover_text("restarts the scene and records your input")
                .clicked()
            {
                s.start_recording();
            }
        } else if ui.button("Stop and save").clicked() {
            save_recording(s, st);
        }
    });
    ui.horizontal(|ui| {
        ui.text_edit_singleline(&mut st.trace_path);
        if s.trace_path().is_none() {
            if ui.button("Trace CSV").clicked() {
                let p = std::path::PathBuf::from(&st.trace_path);
                match s.start_trace(&p) {
                    Ok(()) => st.say(format!("tracing to {}", p.display()), false),
                    Err(e) => st.say(format!("{}: {e:#}", p.display()), true),
                }
            }
        } else if ui.button("Stop trace").clicked() {
            match s.stop_trace() {
                Ok(Some(p)) => st.say(format!("trace written to {}", p.display()), false),
                Ok(None) => {}
                Err(e) => st.say(format!("{e:#}"), true),
            }
        }
    });
    ui.horizontal(|ui| {
        let first = matches!(view.view, crate::render::View::First);
        if ui.selectable_label(first, "first person").clicked() && !first {
            view.toggle_view();
        }
        if ui.selectable_label(!first, "orbit").clicked() && first {
            view.toggle_view();
        }
    });
    ui.add(egui::Slider::new(&mut view.knock, 0.0..=1.0).text("view knocked by blows"))
        .on_hover_text("How far a blow you take turns the first-person view (0 = off)");
    ui.horizontal_wrapped(|ui| {
        let o = &mut view.overlays;
        ui.checkbox(&mut o.gaze_rays, "gaze rays");
        ui.checkbox(&mut o.fov_cones, "fields of view");
        ui.checkbox(&mut o.saliency_labels, "saliency labels");
        ui.checkbox(&mut o.joint_frames, "joint frames");
    });
}

/// Stop the recording and write it where the panel says.
pub fn save_recording(s: &mut Session, st: &mut PanelState) {
    let path = std::path::PathBuf::from(&st.record_path);
    match s.stop_recording() {
        Ok(Some(text)) => match std::fs::write(&path, text) {
            Ok(()) => st.say(
                format!(
                    "session saved to {} (replay: shisen run {} --headless)",
                    path.display(),
                    path.display()
                ),
                false,
            ),
            Err(e) => st.say(format!("{}: {e}", path.display()), true),
        },
        Ok(None) => {}
        Err(e) => st.say(format!("{e:#}"), true),
    }
}

fn attention(ui: &mut egui::Ui, s: &Session) {
    let Some(last) = s.sim.last() else { return };
    ui.label(format!(
        "winner: {} ({}), amount {:.2}",
        last.gaze_target,
        last.source.as_str(),
        last.amount
    ));
    let scores: Vec<(String, f64)> = s
        .sim
        .seen()
        .iter()
        .map(|v| {
            (
                s.sim.world.info(v.body).name.clone(),
                s.sim.attention.scores[v.body.index()],
            )
        })
        .collect();
    let top = scores
        .iter()
        .map(|x| x.1)
        .chain([last.amount])
        .fold(1e-9, f64::max);
    ui.label("bottom-up saliency of every visible body:");
    for (name, score) in &scores {
        let winner = *name == last.gaze_target;
        ui.horizontal(|ui| {
            ui.add_sized(
                [90.0, 16.0],
                egui::Label::new(if winner {
                    RichText::new(name).strong()
                } else {
                    RichText::new(name)
                }),
            );
            ui.add(egui::ProgressBar::new((score / top) as f32).text(format!("{score:.3}")));
        });
    }
    // The action's request carries the personality's amount for it (gaze.md 5).
    let pers = &s.sim.params().personality;
    let top_down = match last.action {
        shisen_gaze::behaviour::ActionKind::Idle => pers.a_face,
        shisen_gaze::behaviour::ActionKind::Attack => pers.a_attack,
        _ => pers.a_guard,
    };
    ui.horizontal(|ui| {
        ui.add_sized([90.0, 16.0], egui::Label::new("top-down"));
        ui.add(
            egui::ProgressBar::new((top_down / top.max(top_down)) as f32)
                .fill(egui::Color32::from_rgb(90, 140, 60))
                .text(format!("{top_down:.3} ({:?})", last.action)),
        );
    });
}

fn personality(ui: &mut egui::Ui, s: &mut Session) {
    let mut p = s.sim.params().personality.clone();
    let mut changed = false;
    for (label, v) in [
        ("A_face", &mut p.a_face),
        ("A_attack", &mut p.a_attack),
        ("A_guard", &mut p.a_guard),
        ("A1 (head moves least)", &mut p.a1),
        ("A2 (head moves most)", &mut p.a2),
    ] {
        changed |= ui
            .add(egui::Slider::new(v, 0.0..=5.0).text(label))
            .changed();
    }
    if changed {
        if p.a2 <= p.a1 {
            p.a2 = p.a1 + 0.01;
        }
        s.sim.edit_params(|m| m.personality = p);
    }
    let mut rate = s.sim.params().behaviour.attack_rate;
    if ui
        .add(egui::Slider::new(&mut rate, 0.0..=2.0).text("attack rate (1/s)"))
        .changed()
    {
        s.sim.edit_params(|m| m.behaviour.attack_rate = rate);
    }
}

fn gains(ui: &mut egui::Ui, s: &mut Session, st: &mut PanelState) {
    ui.horizontal(|ui| {
        ui.text_edit_singleline(&mut st.gains_path);
        if ui.button("Load gains").clicked() {
            let p = std::path::PathBuf::from(&st.gains_path);
            let loaded = shisen::physics::control::Gains::load(&p)
                .map_err(|e| e.to_string())
                .and_then(|g| {
                    shisen::physics::plausible::check_gains(&g)
                        .map(|()| g)
                        .map_err(|m| m.to_string())
                });
            match loaded {
                Ok(g) => {
                    s.sim.edit_params(|m| m.gains = g);
                    st.say(format!("gains from {}", p.display()), false);
                }
                Err(e) => st.say(e, true),
            }
        }
    });
    let mut g = s.sim.params().gains.clone();
    let mut changed = false;
    for group in Group::ALL {
        ui.label(RichText::new(format!("{group:?}")).strong());
        let jg = g.group_mut(group);
        ui.horizontal(|ui| {
            let (kp_speed, kd_speed) = (jg.kp * 0.01 + 1e-4, jg.kd * 0.01 + 1e-5);
            changed |= ui
                .add(
                    egui::DragValue::new(&mut jg.kp)
                        .speed(kp_speed)
                        .range(0.0..=1e4)
                        .prefix("kp "),
                )
                .changed();
            changed |= ui
                .add(
                    egui::DragValue::new(&mut jg.kd)
                        .speed(kd_speed)
                        .range(0.0..=1e3)
                        .prefix("kd "),
                )
                .changed();
            if ui.button("step response").clicked() {
                st.step = Some(step_response(&s.sim.params().gains, group));
            }
        });
    }
    if changed {
        s.sim.edit_params(|m| m.gains = g);
    }
    ui.label("live target (dashed) vs actual, degrees:");
    let series = |f: &dyn Fn(&shisen::sim::Sample) -> f64| -> PlotPoints<'static> {
        s.history.iter().map(|x| [x.t, f(x).to_degrees()]).collect()
    };
    Plot::new("joint plot")
        .height(160.0)
        .legend(Legend::default())
        .show(ui, |p| {
            p.line(
                Line::new("eye L yaw target", series(&|x| x.eye_target[0].x))
                    .style(egui_plot::LineStyle::dashed_loose()),
            );
            p.line(Line::new("eye L yaw", series(&|x| x.eye_actual[0].x)));
            p.line(
                Line::new("neck yaw target", series(&|x| x.neck_target.yaw))
                    .style(egui_plot::LineStyle::dashed_loose()),
            );
            p.line(Line::new("neck yaw", series(&|x| x.neck_actual.yaw)));
            p.line(
                Line::new("neck pitch target", series(&|x| x.neck_target.pitch))
                    .style(egui_plot::LineStyle::dashed_loose()),
            );
            p.line(Line::new("neck pitch", series(&|x| x.neck_actual.pitch)));
        });
    if let Some(r) = &st.step {
        let m = &r.report;
        ui.label(format!(
            "{:?} step ({:?}): rise {:.0} ms, overshoot {:.1} % (max {:.0} %), settling {:.0} ms (max {:.0} ms){}",
            r.group,
            r.objective.step,
            m.rise_time * 1e3,
            m.overshoot * 100.0,
            r.objective.max_overshoot * 100.0,
            m.settling_time * 1e3,
            r.objective.max_settling * 1e3,
            if m.unstable.is_some() { ", UNSTABLE" } else { "" }
        ));
        let deg = |v: &[f64]| -> PlotPoints<'static> {
            r.response
                .t
                .iter()
                .zip(v)
                .map(|(t, y)| [*t, y.to_degrees()])
                .collect()
        };
        Plot::new("step plot").height(120.0).show(ui, |p| {
            p.line(Line::new("response", deg(&r.response.actual)));
            p.line(
                Line::new("target", deg(&r.response.reference))
                    .style(egui_plot::LineStyle::dashed_loose()),
            );
        });
    }
}

fn face(ui: &mut egui::Ui, s: &mut Session, st: &mut PanelState) {
    ui.label(format!("current: {:?}", s.sim.face_state.emotion));
    egui::ComboBox::from_label("emotion")
        .selected_text(format!("{:?}", st.emotion))
        .height(400.0)
        .show_ui(ui, |ui| {
            for e in Emotion::all() {
                ui.selectable_value(&mut st.emotion, e, format!("{e:?}"));
            }
        });
    ui.add(egui::Slider::new(&mut st.intensity, 0.0..=1.0).text("intensity"));
    ui.horizontal(|ui| {
        for (sp, label) in [
            (Speed::Fast, "1 fast"),
            (Speed::Typical, "2 typical"),
            (Speed::Slow, "3 slow"),
        ] {
            ui.radio_value(&mut st.speed, sp, label);
        }
    });
    if ui.button("Show emotion").clicked() {
        s.push(Event {
            at: 0.0, // set to now by Session::push
            action: Action::Emotion {
                emotion: st.emotion,
                intensity: st.intensity as f64,
                speed: st.speed,
                pattern: Pattern::III,
            },
        });
    }
    ui.separator();
    ui.label("Action Units (both sides; not recorded):");
    let au = &mut s.sim.face_state.au;
    for (i, a) in ActionUnit::ALL.into_iter().enumerate() {
        let mut v = au.left[i].max(au.right[i]);
        if ui
            .add(egui::Slider::new(&mut v, 0.0..=1.0).text(format!("{a:?}")))
            .changed()
        {
            au.set(a, v);
        }
    }
}
