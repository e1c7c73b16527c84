//! Plots as PNG: trace plots (gaze, eye and head angles against time with
//! the gaze-target switches marked) and generic line charts used by the
//! tuning tools. Drawn with plotters into a buffer, encoded by `image`.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Once;

use anyhow::{Context, Result, bail};
use plotters::prelude::*;

/// One line of a chart.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Stroke,
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stroke {
    /// A solid line.
    Solid,
    /// A dashed line (references).
    Dashed,
    /// Unconnected dots (scatter).
    Dots,
}

/// One panel of a chart: a title, a y-axis label and its lines.
#[derive(Clone, Debug)]
pub struct Panel {
    /// Panel title.
    pub title: String,
    /// Y-axis label.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
}

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        // egui's shipped font; no system font is needed.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}

/// Write `text` centred at (`x`, `y`) (pixels, top of the text) on an RGB
/// image, light grey, `px` pixels high (captions of contact sheets).
pub fn caption(image: &mut image::RgbImage, x: i32, y: i32, text: &str, px: u32) -> Result<()> {
    register_font();
    let (w, h) = image.dimensions();
    let root = BitMapBackend::with_buffer(image.as_mut(), (w, h)).into_drawing_area();
    let style = ("sans-serif", px)
        .into_font()
        .color(&RGBColor(225, 225, 225))
        .pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Center,
            plotters::style::text_anchor::VPos::Top,
        ));
    root.draw_text(text, &style, (x, y))
        .map_err(|e| anyhow::anyhow!("caption {text:?}: {e}"))?;
    root.present()
        .map_err(|e| anyhow::anyhow!("caption {text:?}: {e}"))?;
    Ok(())
}

const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
];

/// Draw stacked panels sharing the x axis (`x_label`), with vertical
/// `markers` (x, label) on every panel, and write a PNG.
pub fn chart(
    out: &Path,
    size: (u32, u32),
    x_label: &str,
    panels: &[Panel],
    markers: &[(f64, String)],
) -> Result<()> {
    register_font();
    if panels.is_empty() {
        bail!("nothing to plot");
    }
    let (w, h) = size;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        let areas = root.split_evenly((panels.len(), 1));
        let x_range = panels
            .iter()
            .flat_map(|p| p.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        if !x_range.0.is_finite() {
            bail!("no data points");
        }
        let x_range = if x_range.1 > x_range.0 {
            x_range
        } else {
            (x_range.0, x_range.0 + 1.0)
        };
        for (panel, area) in panels.iter().zip(areas.iter()) {
            let (lo, hi) = panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1))
                .filter(|y| y.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                    (a.min(y), b.max(y))
                });
            let (lo, hi) = if lo.is_finite() && hi > lo {
                let pad = 0.08 * (hi - lo);
                (lo - pad, hi + pad)
            } else if lo.is_finite() {
                (lo - 1.0, lo + 1.0)
            } else {
                (-1.0, 1.0)
            };
            let mut c = ChartBuilder::on(area)
                .caption(&panel.title, ("sans-serif", 18))
                .margin(8)
                .x_label_area_size(30)
                .y_label_area_size(55)
                .build_cartesian_2d(x_range.0..x_range.1, lo..hi)?;
            c.configure_mesh()
                .x_desc(x_label)
                .y_desc(&panel.y_label)
                .label_style(("sans-serif", 13))
                .draw()?;
            for (x, label) in markers {
                c.draw_series(LineSeries::new([(*x, lo), (*x, hi)], BLACK.mix(0.25)))?;
                c.draw_series(std::iter::once(Text::new(
                    label.clone(),
                    (*x, hi - 0.04 * (hi - lo)),
                    ("sans-serif", 11).into_font().color(&BLACK.mix(0.6)),
                )))?;
            }
            for (i, s) in panel.series.iter().enumerate() {
                let color = COLORS[i % COLORS.len()];
                let style = color.stroke_width(2);
                let pts = s.points.iter().copied().filter(|p| p.1.is_finite());
                match s.style {
                    Stroke::Dashed => c.draw_series(DashedLineSeries::new(pts, 6, 4, style))?,
                    Stroke::Solid => c.draw_series(LineSeries::new(pts, style))?,
                    Stroke::Dots => {
                        c.draw_series(pts.map(|p| Circle::new(p, 3, color.filled())))?
                    }
                }
                .label(&s.label)
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2))
                });
            }
            c.configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.3))
                .label_font(("sans-serif", 12))
                .draw()?;
        }
        root.present()?;
    }
    let img = image::RgbImage::from_raw(w, h, buf).context("plot buffer size")?;
    img.save(out)
        .with_context(|| format!("cannot write {}", out.display()))?;
    Ok(())
}

/// A parsed trace CSV: column name -> values (numbers where they parse).
pub struct TraceTable {
    /// The file it came from (for messages).
    file: String,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
    index: HashMap<String, usize>,
}

impl TraceTable {
    /// Parse trace text (CSV, header first, quoted cells allowed).
    pub fn parse(text: &str, file: &str) -> Result<Self> {
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(text.as_bytes());
        let mut records = reader.records();
        let bad = |e: csv::Error| match e.kind() {
            csv::ErrorKind::UnequalLengths {
                pos,
                expected_len,
                len,
            } => anyhow::anyhow!(
                "{file}:{}: {len} fields, the header has {expected_len}",
                pos.as_ref().map_or(0, |p| p.line())
            ),
            _ => anyhow::anyhow!("{file}: {e}"),
        };
        let header: Vec<String> = records
            .next()
            .with_context(|| format!("{file}: empty trace"))?
            .map_err(bad)?
            .iter()
            .map(String::from)
            .collect();
        let index = header
            .iter()
            .enumerate()
            .map(|(i, h)| (h.clone(), i))
            .collect();
        let mut rows = Vec::new();
        for r in records {
            rows.push(r.map_err(bad)?.iter().map(String::from).collect());
        }
        Ok(TraceTable {
            file: file.to_string(),
            header,
            rows,
            index,
        })
    }

    /// Numeric column (NaN where a cell is not a number).
    pub fn column(&self, name: &str) -> Result<Vec<f64>> {
        let i = *self.index.get(name).with_context(|| {
            format!(
                "{}:1: the trace has no column `{name}` (its columns: {})",
                self.file,
                self.header.join(", ")
            )
        })?;
        Ok(self
            .rows
            .iter()
            .map(|r| r[i].parse().unwrap_or(f64::NAN))
            .collect())
    }

    /// Text column.
    pub fn text(&self, name: &str) -> Result<Vec<&str>> {
        let i = *self
            .index
            .get(name)
            .with_context(|| format!("{}:1: the trace has no column `{name}`", self.file))?;
        Ok(self.rows.iter().map(|r| r[i].as_str()).collect())
    }
}

/// A trace's time column is simulation time: finite, within a day (the
/// longest run), rising from row to row. The error names the row's line.
fn check_time(t: &[f64], file: &str) -> Result<()> {
    let mut last = f64::NEG_INFINITY;
    for (i, &v) in t.iter().enumerate() {
        let line = i + 2; // the header is line 1
        if !v.is_finite() || !(0.0..=86_400.0).contains(&v) {
            anyhow::bail!("{file}:{line}: t = {v}: a trace's time is 0 to 86400 s");
        }
        if v <= last {
            anyhow::bail!("{file}:{line}: t = {v} after {last}: a trace's time must rise");
        }
        last = v;
    }
    Ok(())
}

/// Plot a trace: gaze, eye and head yaw and pitch against time, the
/// line-of-sight error, and the gaze-target switches marked.
pub fn plot_trace(trace: &Path, out: &Path, size: (u32, u32)) -> Result<()> {
    // A trace is data, up to an hour of ticks: 2 GiB at most.
    let text =
        shisen_gaze::util::ron::read_text_up_to(trace, 2 << 30).context("cannot read the trace")?;
    let file = trace.display().to_string();
    let tt = TraceTable::parse(&text, &file)?;
    let t = tt.column("t")?;
    check_time(&t, &file)?;
    let zip = |a: &[f64]| t.iter().copied().zip(a.iter().copied()).collect::<Vec<_>>();
    let eye_y = tt.column("eye_l_yaw")?;
    let eye_p = tt.column("eye_l_pitch")?;
    let head_y = tt.column("head_yaw")?;
    let head_p = tt.column("head_pitch")?;
    // Gaze in the world: the face's direction plus the eye in the head.
    let gaze_y: Vec<f64> = head_y.iter().zip(&eye_y).map(|(h, e)| h + e).collect();
    let gaze_p: Vec<f64> = head_p.iter().zip(&eye_p).map(|(h, e)| h + e).collect();
    let s = |label: &str, v: &[f64], dashed: bool| Series {
        label: label.into(),
        points: zip(v),
        style: if dashed {
            Stroke::Dashed
        } else {
            Stroke::Solid
        },
    };
    let panels = vec![
        Panel {
            title: "yaw (+ left)".into(),
            y_label: "deg".into(),
            series: vec![
                s("gaze", &gaze_y, false),
                s("eye (left, in head)", &eye_y, false),
                s("head", &head_y, false),
                s("eye target", &tt.column("eye_l_yaw_tgt")?, true),
            ],
        },
        Panel {
            title: "pitch (+ up)".into(),
            y_label: "deg".into(),
            series: vec![
                s("gaze", &gaze_p, false),
                s("eye (left, in head)", &eye_p, false),
                s("head", &head_p, false),
                s("eye target", &tt.column("eye_l_pitch_tgt")?, true),
            ],
        },
        Panel {
            title: "line-of-sight error".into(),
            y_label: "deg".into(),
            series: vec![
                s("left eye", &tt.column("los_err_l")?, false),
                s("right eye", &tt.column("los_err_r")?, false),
            ],
        },
    ];
    let targets = tt.text("gaze_target")?;
    let mut markers = Vec::new();
    for i in 0..targets.len() {
        if i == 0 || targets[i] != targets[i - 1] {
            markers.push((t[i], targets[i].to_string()));
        }
    }
    chart(out, size, "time (s)", &panels, &markers)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trace_table_rejects_ragged_rows_with_the_line() {
        let e = TraceTable::parse("a,b\n1,2\n3\n", "x.csv")
            .err()
            .unwrap()
            .to_string();
        assert!(e.starts_with("x.csv:3:"), "{e}");
    }

    #[test]
    fn a_trace_whose_time_is_not_time_is_refused_at_its_line() {
        for (t, line) in [
            (vec![0.001, f64::NAN], 3),
            (vec![0.002, 0.001], 3),
            (vec![1e300], 2),
            (vec![-1.0], 2),
        ] {
            let e = check_time(&t, "t.csv").unwrap_err().to_string();
            assert!(e.starts_with(&format!("t.csv:{line}:")), "{e}");
        }
        assert!(check_time(&[0.001, 0.002], "t.csv").is_ok());
    }

    #[test]
    fn chart_writes_a_png() {
        let dir = std::env::temp_dir().join(format!("shisen-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("c.png");
        let panel = Panel {
            title: "sine".into(),
            y_label: "y".into(),
            series: vec![Series {
                label: "sin".into(),
                points: (0..100)
                    .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
                    .collect(),
                style: Stroke::Solid,
            }],
        };
        chart(&out, (400, 300), "x", &[panel], &[(2.0, "mark".into())]).unwrap();
        let img = image::open(&out).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (400, 300));
        assert!(
            img.pixels().any(|p| p.0 != [255, 255, 255]),
            "something was drawn"
        );
    }
}
