//! `shisen face`: export and calibrate the face.

use anyhow::{Context, Result};

use crate::cli::*;
use shisen::tools::output::{Outputs, write_whole};

pub fn face_cmd(c: FaceCommand) -> Result<()> {
    use shisen::face::{Face, calibrate, exchange, mesh::MeshParams, params::FaceParams};
    match c {
        FaceCommand::Export { out, rows } => {
            // The head's landmarks beside it, so it can be imported again
            // (a scene's `vh.face.mesh` and `vh.face.landmarks`).
            let landmarks = out.with_extension("landmarks.ron");
            Outputs::new()
                .file_as("--out", &out, "a binary glTF head", &["glb"])
                .file("--out (landmarks)", &landmarks)
                .check()?;
            let face = Face::new(MeshParams { rows }, FaceParams::default_params());
            write_whole(&out, &exchange::export_glb(&face))
                .with_context(|| format!("cannot write {}", out.display()))?;
            let lm = shisen::face::import::LandmarkFile::from_landmarks(&face.mesh.landmarks);
            write_whole(&landmarks, lm.to_ron().as_bytes())
                .with_context(|| format!("cannot write {}", landmarks.display()))?;
            println!(
                "{}: {} vertices, {} triangles, morph targets per muscle and ARKit shape; landmarks in {}",
                out.display(),
                face.mesh.positions.len(),
                face.mesh.triangles.len(),
                landmarks.display()
            );
        }
        FaceCommand::Sheet {
            out,
            rows,
            cell,
            basic,
        } => {
            Outputs::new()
                .file_as("--out", &out, "a PNG picture", &["png"])
                .check()?;
            sheet(&out, rows, cell, basic)?
        }
        FaceCommand::Calibrate { csv, out } => {
            Outputs::new()
                .input(&csv)
                .file_as("--out", &out, "a muscle database (RON)", &["ron"])
                .check()?;
            let params = calibrate::calibrate_file(&FaceParams::default_params(), &csv)?;
            write_whole(&out, params.to_ron().as_bytes())
                .with_context(|| format!("cannot write {}", out.display()))?;
            println!("muscle database written to {}", out.display());
        }
    }
    Ok(())
}

/// Columns of the contact sheet (35 emotions: 7 x 5).
const SHEET_COLUMNS: u32 = 7;
/// Caption band under each face, pixels.
const CAPTION: u32 = 22;

/// Every emotion at full intensity, 1.5 s after a fast onset, from the
/// face camera, in one captioned grid.
fn sheet(out: &std::path::Path, rows: usize, cell: (u32, u32), basic: bool) -> Result<()> {
    use shisen::face::tables::Emotion;
    use shisen::scene::LoadedScene;
    use shisen_app::render::{Headless, Overlays, View, write_png};
    // (emotion, intensity, view, caption), row by row.
    let three_quarter = View::Orbit {
        yaw: 0.65,
        pitch: 0.05,
        distance: 0.45,
    };
    let all: Vec<(Emotion, f64, View, String)> = if basic {
        let basics = [
            Emotion::Neutral,
            Emotion::Happiness,
            Emotion::Surprise,
            Emotion::Fear,
            Emotion::Sadness,
            Emotion::Disgust,
            Emotion::Anger,
        ];
        let conditions = [
            (1.0, View::FACE, "front"),
            (0.6, View::FACE, "front 60%"),
            (1.0, three_quarter, "3/4"),
            (0.6, three_quarter, "3/4 60%"),
        ];
        conditions
            .iter()
            .flat_map(|&(i, v, c)| basics.map(|e| (e, i, v, format!("{e:?} {c}"))))
            .collect()
    } else {
        Emotion::all()
            .map(|e| (e, 1.0, View::FACE, format!("{e:?}")))
            .collect()
    };
    let n = all.len() as u32;
    let (cw, ch) = (cell.0, cell.1 + CAPTION);
    let grid = (SHEET_COLUMNS, n.div_ceil(SHEET_COLUMNS));
    let mut sheet = image::RgbImage::from_pixel(cw * grid.0, ch * grid.1, image::Rgb([30, 32, 38]));
    let mut gpu = Headless::new()?;
    for (k, (e, intensity, view, label)) in all.iter().enumerate() {
        let text = format!(
            "Scene(duration: 2.0, vh: (behaviour: (attacks: false), oculomotor: (fixation: (enabled: false)), face: (rows: {rows})), timeline: [(at: 0.0, do: Emotion(emotion: {e:?}, intensity: {intensity}, speed: Fast))])"
        );
        let loaded = LoadedScene::from_str(&text, std::path::Path::new("<sheet>"), None)?;
        let mut sim = loaded.sim();
        while sim.time() < 1.5 {
            sim.step();
        }
        if shisen::tools::stop_requested() {
            return Err(crate::run::Interrupted(format!(
                "after {k} of {n} faces; nothing written"
            ))
            .into());
        }
        let face = gpu.snapshot(&sim, *view, Overlays::default(), cell)?;
        let (x, y) = ((k as u32 % grid.0) * cw, (k as u32 / grid.0) * ch);
        for (px, py, p) in face.enumerate_pixels() {
            sheet.put_pixel(x + px, y + py, image::Rgb([p[0], p[1], p[2]]));
        }
        shisen::tools::plot::caption(
            &mut sheet,
            (x + cw / 2) as i32,
            (y + cell.1 + 3) as i32,
            label,
            16,
        )?;
    }
    write_png(&image::DynamicImage::ImageRgb8(sheet).to_rgba8(), out)?;
    println!(
        "{}: {n} faces, {}x{} each, {rows} rows",
        out.display(),
        cell.0,
        cell.1
    );
    Ok(())
}
