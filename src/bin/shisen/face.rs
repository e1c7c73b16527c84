//! `shisen face`: export and calibrate the face.

use anyhow::{Context, Result};

use crate::cli::*;

pub fn face_cmd(c: FaceCommand) -> Result<()> {
    use shisen::face::{Face, calibrate, exchange, mesh::MeshParams, params::FaceParams};
    match c {
        FaceCommand::Export { out, rows } => {
            if !(24..=400).contains(&rows) {
                anyhow::bail!("--rows: must be 24-400, got {rows}");
            }
            let face = Face::new(MeshParams { rows }, FaceParams::default_params());
            std::fs::write(&out, exchange::export_glb(&face))
                .with_context(|| format!("cannot write {}", out.display()))?;
            println!(
                "{}: {} vertices, {} triangles, morph targets per muscle and ARKit shape",
                out.display(),
                face.mesh.positions.len(),
                face.mesh.triangles.len()
            );
        }
        FaceCommand::Calibrate { csv, out } => {
            let params = calibrate::calibrate_file(&FaceParams::default_params(), &csv)?;
            std::fs::write(&out, params.to_ron())
                .with_context(|| format!("cannot write {}", out.display()))?;
            println!("muscle database written to {}", out.display());
        }
    }
    Ok(())
}
