//! The bout's face in the window: the scoreboard over the view (round,
//! clock, punches landed and thrown, the VH's stamina, the bell's
//! banners), the menu (opponent, rounds, restart, report, replay, quit),
//! the round report, and the replay's scrubber. Sizes follow the view's
//! height, so the figures stay legible at arm's length in any window.

use std::path::PathBuf;

use eframe::egui::{self, Align2, Color32, FontId, Pos2, Rect, RichText, Stroke, vec2};

use shisen::scene::opponent::{Level, Opponent, Style};
use shisen::sim::blows::{BlowKind, Fighter};
use shisen::sim::bout::{Bell, BoutParams, Phase};
use shisen::sim::stats::{Card, FighterStats};
use shisen_gaze::behaviour::ActionKind;

use super::bout::Look;
use super::session::Session;
use crate::render::Panel;

const PANEL: Color32 = Color32::from_rgba_premultiplied(8, 10, 14, 200);
const YOU: Color32 = Color32::from_rgb(90, 150, 255);
const VH: Color32 = Color32::from_rgb(235, 70, 60);
const GOLD: Color32 = Color32::from_rgb(255, 215, 110);

/// The window's bout state that is not simulation state.
pub struct BoutUi {
    /// The menu is open (the bout paused).
    pub menu: bool,
    /// The report is open, on this round (0: the whole bout).
    pub report: Option<u32>,
    /// The developer figures (frame time, sim time, the VH's action and
    /// gaze) are shown.
    pub dev: bool,
    /// The opponent chosen in the menu.
    pub opponent: Opponent,
    /// The bout chosen in the menu (`None`: open sparring).
    pub bout: Option<BoutParams>,
    /// The bout was paused by the menu (resume on closing it).
    paused_by_menu: bool,
    /// Where the report was drawn last frame (for its PNG).
    pub report_rect: Option<Rect>,
    /// A PNG of the report was asked for, to this path.
    pub report_png: Option<PathBuf>,
    /// The last message (a saved file, an error).
    pub status: Option<String>,
    /// Sound volume, 0-1, and whether it is muted (F4).
    pub volume: f32,
    pub muted: bool,
}

impl BoutUi {
    /// The state for a session that starts with `opponent` and `bout`.
    pub fn new(opponent: Opponent, bout: Option<BoutParams>) -> Self {
        BoutUi {
            menu: false,
            report: None,
            dev: false,
            opponent,
            bout,
            paused_by_menu: false,
            report_rect: None,
            report_png: None,
            status: None,
            volume: 1.0,
            muted: false,
        }
    }

    /// Open or close the menu, pausing the bout while it is open.
    pub fn toggle_menu(&mut self, s: &mut Session) {
        self.menu = !self.menu;
        if self.menu {
            self.paused_by_menu = !s.clock.paused;
            s.clock.paused = true;
        } else if self.paused_by_menu {
            s.clock.paused = false;
            self.paused_by_menu = false;
        }
    }

    /// Open or close the report on the round under way (or just fought).
    pub fn toggle_report(&mut self, s: &Session) {
        self.report = match self.report {
            Some(_) => None,
            None => Some(round_now(s).unwrap_or(0)),
        };
    }
}

/// What the menu asks of the app.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MenuAction {
    /// Start the bout again with the menu's opponent and rounds.
    Fight,
    /// Close the window.
    Quit,
}

fn round_now(s: &Session) -> Option<u32> {
    let b = s.sim.model().bout?;
    Some(s.sim.phase(s.sim.time())?.0.round(&b))
}

/// "2:05".
fn clock(secs: f64) -> String {
    let s = secs.max(0.0).ceil() as u64;
    format!("{}:{:02}", s / 60, s % 60)
}

/// The scoreboard over the view `rect`, of `sim`: the bout, or its replay
/// (whose clock and statistics are its own; the bell's banners and the
/// last blow are the live bout's, and are not shown over a replay). Its
/// text is painted; its panels are returned, for the view's blit to lay
/// under the text ([`crate::render::Blit`]: a software rasteriser fills
/// them there for a fraction of egui's cost).
pub fn scoreboard(ui: &egui::Ui, rect: Rect, s: &Session, sim: &shisen::sim::Sim) -> Vec<Panel> {
    let live = s.replay.is_none();
    let p = ui.painter_at(rect);
    let ppp = ui.ctx().pixels_per_point();
    let mut fills = Vec::new();
    let mut fill = |r: Rect, radius: f32, color: Color32| {
        fills.push(Panel {
            min: [r.min.x * ppp, r.min.y * ppp],
            max: [r.max.x * ppp, r.max.y * ppp],
            radius: radius * ppp,
            color: color.to_array(),
        });
    };
    let h = rect.height();
    let big = FontId::proportional((h / 15.0).clamp(22.0, 72.0));
    let mid = FontId::proportional((h / 30.0).clamp(15.0, 36.0));
    let small = FontId::proportional((h / 48.0).clamp(12.0, 24.0));
    let t = sim.time();
    let card = sim.stats.total();
    // The clock, top centre.
    let (title, time) = match (sim.model().bout, sim.phase(t)) {
        (Some(b), Some((Phase::Round(n), left))) => {
            (format!("ROUND {n}/{}", b.rounds), clock(left))
        }
        (Some(_), Some((Phase::Rest(n), left))) => (format!("REST AFTER {n}"), clock(left)),
        (Some(_), Some((Phase::Over, _))) => ("FINAL".to_string(), String::new()),
        _ => ("SPARRING".to_string(), clock(t)),
    };
    let top = rect.center_top() + vec2(0.0, h * 0.015);
    let w = big.size * 4.2;
    let box_ = Rect::from_min_size(
        top - vec2(w / 2.0, 0.0),
        vec2(w, big.size * 1.05 + mid.size * 1.3),
    );
    fill(box_, 6.0, PANEL);
    p.text(
        box_.center_top() + vec2(0.0, mid.size * 0.15),
        Align2::CENTER_TOP,
        title,
        mid.clone(),
        GOLD,
    );
    p.text(
        box_.center_top() + vec2(0.0, mid.size * 1.25),
        Align2::CENTER_TOP,
        time,
        big.clone(),
        Color32::WHITE,
    );
    // The distance between you and the range it is, under the clock.
    p.text(
        box_.center_bottom() + vec2(0.0, h * 0.006),
        Align2::CENTER_TOP,
        format!(
            "{:.2} m  {}",
            sim.distance(),
            sim.zone().name().to_uppercase()
        ),
        small.clone(),
        Color32::LIGHT_GRAY,
    );
    // The fighters' punches, either side of the clock.
    let mut side = |f: &FighterStats, name: &str, color: Color32, left: bool| {
        let lines = [
            (name.to_string(), mid.clone(), color),
            (
                format!("landed {}", f.total().show()),
                mid.clone(),
                Color32::WHITE,
            ),
            (
                format!(
                    "jabs {}   power {}",
                    f.jabs.show_short(),
                    f.power.show_short()
                ),
                small.clone(),
                Color32::LIGHT_GRAY,
            ),
        ];
        let width = mid.size * 10.0;
        let x = if left {
            box_.min.x - width - h * 0.01
        } else {
            box_.max.x + h * 0.01
        };
        let r = Rect::from_min_size(
            Pos2::new(x, box_.min.y),
            vec2(width, mid.size * 2.6 + small.size * 1.4),
        );
        fill(r, 6.0, PANEL);
        let mut y = r.min.y + mid.size * 0.15;
        let align = if left {
            Align2::RIGHT_TOP
        } else {
            Align2::LEFT_TOP
        };
        let ax = if left {
            r.max.x - mid.size * 0.4
        } else {
            r.min.x + mid.size * 0.4
        };
        for (text, font, c) in lines {
            let size = font.size;
            p.text(Pos2::new(ax, y), align, text, font, c);
            y += size * 1.2;
        }
        r
    };
    side(&card.you, "YOU", YOU, true);
    let vh_box = side(&card.vh, "VH", VH, false);
    // The VH's stamina under its figures.
    let fatigue = sim.last().map_or(0.0, |l| l.fatigue) as f32;
    let bar = Rect::from_min_size(
        vh_box.left_bottom() + vec2(0.0, h * 0.008),
        vec2(vh_box.width(), (h / 90.0).max(6.0)),
    );
    fill(bar, 3.0, PANEL);
    fill(
        Rect::from_min_size(bar.min, vec2(bar.width() * (1.0 - fatigue), bar.height())),
        3.0,
        Color32::from_rgb(80, 200, 120).lerp_to_gamma(VH, fatigue),
    );
    p.text(
        bar.left_bottom() + vec2(0.0, 2.0),
        Align2::LEFT_TOP,
        "VH stamina",
        small.clone(),
        Color32::GRAY,
    );
    // The bell's banner for two seconds.
    if let Some((at, bell)) = s.log.bells.last().filter(|_| live)
        && t - at < 2.0
    {
        let text = match bell {
            Bell::Start(n) => format!("ROUND {n}"),
            Bell::End(n) => match sim.phase(t) {
                Some((Phase::Over, _)) => "END OF THE BOUT".to_string(),
                _ => format!("END OF ROUND {n}"),
            },
        };
        let font = FontId::proportional(big.size * 1.3);
        let at = rect.center() - vec2(0.0, h * 0.12);
        let galley = p.layout_no_wrap(text, font, GOLD);
        let r = Rect::from_center_size(at, galley.size() + vec2(40.0, 16.0));
        fill(r, 8.0, PANEL);
        p.galley(r.min + vec2(20.0, 8.0), galley, GOLD);
    }
    // The last blow, under the clock.
    if let Some(lb) = s.last_blow.as_ref().filter(|lb| live && t - lb.t < 1.5) {
        let b = &lb.blow;
        let (what, c) = match (b.by, b.kind) {
            (Fighter::Opponent, BlowKind::Hit) => (format!("you hit its {}", part(b.part)), YOU),
            (Fighter::Opponent, BlowKind::Block) => ("blocked".to_string(), Color32::GRAY),
            (Fighter::Vh, BlowKind::Hit) => (format!("it hit your {}", part(b.part)), VH),
            (Fighter::Vh, BlowKind::Block) => ("you blocked it".to_string(), Color32::GRAY),
        };
        p.text(
            box_.center_bottom() + vec2(0.0, h * 0.075),
            Align2::CENTER_TOP,
            format!("{what}  {:.0} N s", b.impulse),
            mid.clone(),
            c,
        );
    }
    if let Some(n) = sim.count() {
        // The referee's count over a knockdown.
        p.text(
            rect.center() + vec2(0.0, h * 0.05),
            Align2::CENTER_CENTER,
            format!("DOWN  {n}"),
            FontId::proportional(big.size * 1.5),
            GOLD,
        );
    } else if sim.last().is_some_and(|l| l.staggered) {
        p.text(
            rect.center() + vec2(0.0, h * 0.05),
            Align2::CENTER_CENTER,
            "STAGGERED",
            big.clone(),
            GOLD,
        );
    }
    if s.clock.paused && s.replay.is_none() {
        p.text(
            rect.center() + vec2(0.0, h * 0.18),
            Align2::CENTER_CENTER,
            "PAUSED",
            mid.clone(),
            Color32::WHITE,
        );
    }
    // Keys, bottom left, on a dark band (the canvas behind is light).
    let keys = p.layout_no_wrap(
        "Esc menu   F2 report   F6 replay   F3 figures   V view   F4 sound".to_string(),
        small,
        Color32::from_gray(210),
    );
    let at = rect.left_bottom() + vec2(h * 0.015, -h * 0.015 - keys.size().y);
    fill(
        Rect::from_min_size(at - vec2(6.0, 3.0), keys.size() + vec2(12.0, 6.0)),
        4.0,
        PANEL,
    );
    p.galley(at, keys, Color32::from_gray(210));
    fills
}

fn part(name: &str) -> &str {
    match name {
        "torso" => "body",
        "left_glove" | "right_glove" => "glove",
        n => n,
    }
}

trait Short {
    fn show_short(&self) -> String;
}

impl Short for shisen::sim::stats::Count {
    fn show_short(&self) -> String {
        format!("{}/{}", self.landed, self.thrown)
    }
}

/// The developer's line: the VH's action and gaze, the simulation's
/// clock, the frame's time broken down.
pub fn dev_line(ui: &mut egui::Ui, s: &Session, pads: usize, frames: &super::FrameClock) {
    ui.horizontal_wrapped(|ui| {
        if let Some(last) = s.sim.last() {
            ui.label(format!(
                "VH {:?}, looks at {} ({})",
                last.action,
                last.gaze_target,
                last.source.as_str()
            ));
            ui.separator();
            ui.label(format!("fatigue {:.2}", last.fatigue));
        }
        ui.separator();
        let mut clock = format!("sim t = {:.2} s", s.sim.time());
        if s.clock.slow {
            clock.push_str("  slow motion");
        }
        ui.label(clock);
        if let Some(r) = &s.recorder {
            ui.label(RichText::new(format!("REC {} events", r.len())).color(Color32::RED));
        }
        ui.separator();
        ui.label(format!("reach {:.2} m  pads {pads}", s.control.reach));
        ui.separator();
        ui.label(frames.summary()).on_hover_text(
            "wall time between frames, and the app's own CPU time in it: stepping the \
             simulation, describing the scene, recording the render (the rest is egui \
             and the driver)",
        );
    });
}

/// The menu, centred over the view.
pub fn menu(ctx: &egui::Context, st: &mut BoutUi, s: &mut Session) -> Option<MenuAction> {
    let mut action = None;
    let (enter, quit) =
        ctx.input(|i| (i.key_pressed(egui::Key::Enter), i.key_pressed(egui::Key::Q)));
    // (The default fonts have no CJK glyphs: the window's title has 視線.)
    egui::Window::new(RichText::new("shisen").size(24.0))
        .anchor(Align2::CENTER_CENTER, vec2(0.0, 0.0))
        .collapsible(false)
        .resizable(false)
        .default_width(380.0)
        .show(ctx, |ui| {
            ui.spacing_mut().item_spacing.y = 8.0;
            let text = |t: &str| RichText::new(t).size(18.0);
            ui.label(text("Opponent"));
            egui::Grid::new("opponent").num_columns(2).show(ui, |ui| {
                ui.label("level");
                egui::ComboBox::from_id_salt("level")
                    .selected_text(st.opponent.level.name())
                    .show_ui(ui, |ui| {
                        for l in Level::ALL {
                            ui.selectable_value(&mut st.opponent.level, l, l.name());
                        }
                    });
                ui.end_row();
                ui.label("style");
                egui::ComboBox::from_id_salt("style")
                    .selected_text(st.opponent.style.name())
                    .show_ui(ui, |ui| {
                        for x in Style::ALL {
                            ui.selectable_value(&mut st.opponent.style, x, x.name());
                        }
                    });
                ui.end_row();
            });
            ui.separator();
            let mut rounds_on = st.bout.is_some();
            ui.checkbox(&mut rounds_on, text("Rounds"));
            if rounds_on != st.bout.is_some() {
                st.bout = rounds_on.then(BoutParams::default);
            }
            if let Some(b) = &mut st.bout {
                egui::Grid::new("bout").num_columns(2).show(ui, |ui| {
                    ui.label("rounds");
                    ui.add(egui::Slider::new(&mut b.rounds, 1..=12));
                    ui.end_row();
                    ui.label("round, s");
                    ui.add(egui::Slider::new(&mut b.round, 10.0..=300.0).step_by(10.0));
                    ui.end_row();
                    ui.label("rest, s");
                    ui.add(egui::Slider::new(&mut b.rest, 0.0..=120.0).step_by(5.0));
                    ui.end_row();
                });
            }
            ui.separator();
            ui.horizontal(|ui| {
                let mut on = !st.muted;
                ui.checkbox(&mut on, text("Sound (F4)"));
                st.muted = !on;
                ui.add_enabled(
                    on,
                    egui::Slider::new(&mut st.volume, 0.0..=1.0).text("volume"),
                );
            });
            ui.separator();
            ui.horizontal(|ui| {
                if ui.button(text("Fight! (Enter)")).clicked() || enter {
                    action = Some(MenuAction::Fight);
                }
                if ui.button(text("Resume (Esc)")).clicked() {
                    st.toggle_menu(s);
                }
            });
            ui.horizontal(|ui| {
                if ui.button(text("Round report (F2)")).clicked() {
                    st.toggle_report(s);
                }
                if ui.button(text("Replay (F6)")).clicked() {
                    // Close the menu first (its pause lifted), so the bout
                    // runs again when the replay ends.
                    st.toggle_menu(s);
                    s.toggle_replay();
                }
                if ui.button(text("Quit (Q)")).clicked() || quit {
                    action = Some(MenuAction::Quit);
                }
            });
            ui.label(
                RichText::new(
                    "Mouse: move the glove, left/right button punch.  A/D slip, S duck, \
                     W lean back.  Space pause, V view, F1 tuning.",
                )
                .size(13.0)
                .color(Color32::GRAY),
            );
        });
    action
}

/// The round report window.
pub fn report(ctx: &egui::Context, st: &mut BoutUi, s: &Session) {
    let Some(mut round) = st.report else { return };
    let mut open = true;
    let bout = s.sim.model().bout;
    let t = s.sim.time();
    let rounds = s.sim.stats.rounds.len().max(1) as u32;
    let resp = egui::Window::new(RichText::new("Round report").size(20.0))
        .open(&mut open)
        .anchor(Align2::CENTER_CENTER, vec2(0.0, 0.0))
        .collapsible(false)
        .resizable(false)
        .default_width(640.0)
        .show(ctx, |ui| {
            ui.horizontal(|ui| {
                ui.label("round");
                egui::ComboBox::from_id_salt("report round")
                    .selected_text(if round == 0 {
                        "the bout".to_string()
                    } else {
                        round.to_string()
                    })
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut round, 0, "the bout");
                        for n in 1..=rounds {
                            ui.selectable_value(&mut round, n, n.to_string());
                        }
                    });
                if let Some(o) = s.opponent {
                    ui.label(format!("the VH: {} {}", o.level.name(), o.style.name()));
                }
            });
            let card = if round == 0 {
                s.sim.stats.total()
            } else {
                s.sim
                    .stats
                    .rounds
                    .get(round as usize - 1)
                    .copied()
                    .unwrap_or_default()
            };
            stats_table(ui, &card);
            // The round's time span.
            let (from, to) = match (bout, round) {
                (Some(b), n) if n > 0 => {
                    let start = (n - 1) as f64 * (b.round + b.rest);
                    (start, (start + b.round).min(t))
                }
                _ => (0.0, t),
            };
            ui.add_space(6.0);
            timeline(ui, s, from, to.max(from + 1e-3));
            ui.horizontal(|ui| {
                if ui.button("Save PNG").clicked() {
                    let name = if round == 0 {
                        "shisen-report-bout.png".to_string()
                    } else {
                        format!("shisen-report-round-{round}.png")
                    };
                    st.report_png = Some(PathBuf::from(name));
                }
                if let Some(msg) = &st.status {
                    ui.label(RichText::new(msg).color(Color32::GRAY));
                }
            });
        });
    st.report_rect = resp.map(|r| r.response.rect);
    st.report = open.then_some(round);
}

/// Punch statistics as broadcasts show them: landed/thrown and the
/// percentage, total, jabs and power punches, for each fighter.
fn stats_table(ui: &mut egui::Ui, c: &Card) {
    let size = 17.0;
    egui::Grid::new("punch stats")
        .num_columns(3)
        .spacing(vec2(28.0, 6.0))
        .striped(true)
        .show(ui, |ui| {
            ui.label("");
            ui.label(RichText::new("YOU").size(size).color(YOU).strong());
            ui.label(RichText::new("VH").size(size).color(VH).strong());
            ui.end_row();
            let row = |ui: &mut egui::Ui, name: &str, a: String, b: String| {
                ui.label(RichText::new(name).size(size));
                ui.label(RichText::new(a).size(size));
                ui.label(RichText::new(b).size(size));
                ui.end_row();
            };
            row(
                ui,
                "total punches",
                c.you.total().show(),
                c.vh.total().show(),
            );
            row(ui, "jabs", c.you.jabs.show(), c.vh.jabs.show());
            row(ui, "power punches", c.you.power.show(), c.vh.power.show());
            row(
                ui,
                "landed head / body",
                format!("{} / {}", c.you.head, c.you.body),
                format!("{} / {}", c.vh.head, c.vh.body),
            );
            row(
                ui,
                "blocked by the guard",
                c.you.blocked.to_string(),
                c.vh.blocked.to_string(),
            );
            row(
                ui,
                "missed",
                c.you.missed.to_string(),
                c.vh.missed.to_string(),
            );
            row(ui, "evasions", "-".to_string(), c.vh.evasions.to_string());
            row(ui, "feints", "-".to_string(), c.vh.feints.to_string());
            row(
                ui,
                "knockdowns",
                c.you.knockdowns.to_string(),
                c.vh.knockdowns.to_string(),
            );
            let r = c.range_shares().map(|x| (100.0 * x).round());
            row(
                ui,
                "time at clinch / mid / long / out",
                format!("{} / {} / {} / {} %", r[0], r[1], r[2], r[3]),
                String::new(),
            );
        });
}

fn look_color(l: Look) -> Color32 {
    match l {
        Look::Face => Color32::from_rgb(90, 200, 120),
        Look::Gloves => Color32::from_rgb(240, 160, 50),
        Look::Body => Color32::from_rgb(90, 150, 255),
        Look::Elsewhere => Color32::from_gray(110),
    }
}

fn action_color(a: ActionKind) -> Option<Color32> {
    match a {
        ActionKind::Idle => None,
        ActionKind::Guard => Some(Color32::from_rgb(230, 210, 80)),
        ActionKind::Attack => Some(VH),
        ActionKind::Feint => Some(Color32::from_rgb(120, 190, 230)),
        ActionKind::Slip | ActionKind::Duck | ActionKind::LeanBack => {
            Some(Color32::from_rgb(180, 110, 230))
        }
    }
}

/// Where the VH looked, what it did and the blows both ways, over
/// `[from, to]`.
fn timeline(ui: &mut egui::Ui, s: &Session, from: f64, to: f64) {
    let log = &s.log;
    let span = to - from;
    let shares: Vec<String> = Look::ALL
        .iter()
        .map(|&l| {
            format!(
                "{} {:.0}%",
                l.name(),
                (100.0 * log.looks.share(from, to, l) / span).max(0.0)
            )
        })
        .collect();
    ui.label(RichText::new(format!("where it looked: {}", shares.join("   "))).size(15.0));
    let width = ui.available_width().max(400.0);
    let row_h = 18.0;
    let (rect, _) = ui.allocate_exact_size(vec2(width, row_h * 5.0 + 30.0), egui::Sense::hover());
    let p = ui.painter_at(rect);
    let label_w = 70.0;
    let x = |t: f64| rect.min.x + label_w + ((t - from) / span) as f32 * (width - label_w);
    let rows = ["looked", "did", "blows"];
    for (i, r) in rows.iter().enumerate() {
        p.text(
            Pos2::new(rect.min.x, rect.min.y + row_h * (i as f32 * 1.5 + 0.5)),
            Align2::LEFT_CENTER,
            *r,
            FontId::proportional(13.0),
            Color32::LIGHT_GRAY,
        );
    }
    let band = |i: usize| {
        let y = rect.min.y + row_h * i as f32 * 1.5;
        (y, y + row_h)
    };
    let (y0, y1) = band(0);
    for sp in log.looks.within(from, to) {
        p.rect_filled(
            Rect::from_min_max(
                Pos2::new(x(sp.from), y0),
                Pos2::new(x(sp.to).max(x(sp.from) + 1.0), y1),
            ),
            0.0,
            look_color(sp.what),
        );
    }
    let (y0, y1) = band(1);
    for sp in log.actions.within(from, to) {
        if let Some(c) = action_color(sp.what) {
            p.rect_filled(
                Rect::from_min_max(
                    Pos2::new(x(sp.from), y0),
                    Pos2::new(x(sp.to).max(x(sp.from) + 1.0), y1),
                ),
                0.0,
                c,
            );
        }
    }
    let (y0, y1) = band(2);
    let base = y1 + row_h;
    p.line_segment(
        [Pos2::new(x(from), base), Pos2::new(x(to), base)],
        Stroke::new(1.0, Color32::DARK_GRAY),
    );
    for (bt, b) in log.blows.iter().filter(|(bt, _)| (from..=to).contains(bt)) {
        let c = match (b.by, b.kind) {
            (Fighter::Opponent, BlowKind::Hit) => YOU,
            (Fighter::Vh, BlowKind::Hit) => VH,
            _ => Color32::GRAY,
        };
        // Height by impulse: 30 N s fills the row and a half.
        let top = base - (b.impulse / 30.0).min(1.0) * (base - y0);
        p.line_segment(
            [Pos2::new(x(*bt), base), Pos2::new(x(*bt), top)],
            Stroke::new(2.5, c),
        );
    }
    let (_, ya) = band(2);
    p.text(
        Pos2::new(x(from), ya + row_h * 1.3),
        Align2::LEFT_TOP,
        format!("{:.0} s", from),
        FontId::proportional(12.0),
        Color32::GRAY,
    );
    p.text(
        Pos2::new(x(to), ya + row_h * 1.3),
        Align2::RIGHT_TOP,
        format!("{:.0} s", to),
        FontId::proportional(12.0),
        Color32::GRAY,
    );
    ui.horizontal_wrapped(|ui| {
        for l in Look::ALL {
            ui.colored_label(look_color(l), l.name());
        }
        ui.separator();
        for (name, a) in [
            ("guard", ActionKind::Guard),
            ("attack", ActionKind::Attack),
            ("evade", ActionKind::Slip),
        ] {
            ui.colored_label(action_color(a).expect("coloured"), name);
        }
        ui.separator();
        ui.colored_label(YOU, "| your hits");
        ui.colored_label(VH, "| its hits");
        ui.colored_label(Color32::GRAY, "| blocked (height: impulse, 30 N s full)");
    });
}

/// The replay's bar along the bottom of the view: play/pause, the time
/// scrubber, back to the bout.
pub fn replay_bar(ui: &mut egui::Ui, s: &mut Session) {
    let mut close = false;
    if let Some(r) = &mut s.replay {
        ui.horizontal(|ui| {
            ui.label(RichText::new("REPLAY").strong().color(GOLD).size(18.0));
            let play = if r.playing { "pause" } else { "play" };
            if ui.button(play).clicked() {
                r.playing = !r.playing;
            }
            let mut target = r.target;
            ui.spacing_mut().slider_width = (ui.available_width() - 260.0).max(100.0);
            let resp = ui.add(
                egui::Slider::new(&mut target, 0.0..=r.length.max(0.01))
                    .suffix(" s")
                    .fixed_decimals(1),
            );
            if resp.changed() {
                r.target = target;
            }
            if r.seeking() {
                ui.label(format!("seeking {:.1} s", r.sim.time()));
            }
            if ui.button("back to the bout (F6)").clicked() {
                close = true;
            }
        });
    }
    if close {
        s.toggle_replay();
    }
}
