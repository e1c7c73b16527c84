//! A frame's work: its meshes uploaded and their levels of detail chosen,
//! its uniforms written, then the shadow pass and the scene pass recorded
//! into one submission.

use glam::{Mat3, Mat4, Vec3};

use shisen_face::mesh::HeadMesh;

use super::uniforms::{Globals, Instance, bind};
use super::{CLEAR, INSTANCE_STRIDE, Renderer};
use crate::render::draw::{
    FILL_DIR, KEY_DIR, Material, MeshKey, RIM_DIR, RIM_LIGHT, TOP_DIR, TOP_LIGHT, key_fill_light,
};
use crate::render::frame::{AvatarPart, Frame, Looks};
use crate::render::geometry;
use crate::render::lod::{self, Sight};

/// The levels of detail a frame is drawn at.
struct Detail {
    /// How big things look from the camera.
    sight: Sight,
    /// The head's level (the face and its hair).
    head_level: usize,
    /// The bodies' pieces in view, each at its level, by mesh.
    body_runs: Vec<(MeshKey, Vec<lod::Run>)>,
}

impl Renderer {
    /// [`Renderer::render`], with `then` recording more work after the
    /// frame's into the same submission (given the encoder and the
    /// picture): on lavapipe a second submission waits for the first to
    /// finish, one does not.
    pub fn render_then(
        &mut self,
        frame: &Frame,
        face: &HeadMesh,
        size: (u32, u32),
        then: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::Texture),
    ) -> wgpu::SubmissionIndex {
        self.ensure_target(size);
        let detail = self.upload_meshes(frame, face, size);
        let redo_shadow = self.write_globals(frame);
        self.write_instances(frame);
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("shisen frame"),
            });
        if redo_shadow {
            self.shadow_pass(&mut enc, frame);
        }
        self.scene_pass(&mut enc, frame, &detail);
        if let Some(target) = &self.target {
            then(&mut enc, &target.color);
        }
        self.queue.submit([enc.finish()])
    }

    /// Upload the frame's meshes (capsules not seen before, and the
    /// vertices of the dynamic ones) and choose the levels of detail they
    /// are drawn at in a picture `size` pixels.
    fn upload_meshes(&mut self, frame: &Frame, face: &HeadMesh, size: (u32, u32)) -> Detail {
        for d in &frame.draws {
            if let MeshKey::Capsule {
                half_height,
                radius,
            } = d.mesh
                && !self.meshes.contains_key(&d.mesh)
            {
                let data = geometry::capsule(f32::from_bits(half_height), f32::from_bits(radius));
                self.upload(d.mesh, &data);
            }
        }
        self.dynamic_mesh(
            MeshKey::Face,
            &frame.face,
            &[
                face.triangles.as_flattened(),
                face.medium.as_flattened(),
                face.coarse.as_flattened(),
            ],
        );
        let lashes: Vec<u32> = (0..frame.lashes.len() as u32).collect();
        self.dynamic_mesh(MeshKey::Lashes, &frame.lashes, &[&lashes]);
        let [hair, hair_medium] = &frame.hair.1;
        self.dynamic_mesh(MeshKey::HairShell, &frame.hair.0, &[hair, hair_medium]);
        // The bodies by pieces: those in view, each at its level of detail.
        let looks = Looks::of(&frame.plan);
        let cam = &frame.camera;
        let sight = Sight::new(cam.view_proj(), cam.eye, cam.fov_y, size.1);
        // The head (the face and its hair) at its middle level of detail
        // where that departs from the fine one by under a pixel.
        let head_level = frame
            .draws
            .iter()
            .find(|d| d.mesh == MeshKey::Face)
            .map_or(0, |d| {
                let (centre, radius) = bounding_sphere(&face.positions);
                sight.level(face.medium_error, d.model.transform_point3(centre), radius)
            });
        let mut body_runs = Vec::new();
        for (key, vertices, part) in [
            (MeshKey::Body, &frame.body, AvatarPart::Whole),
            (MeshKey::Avatar, &frame.avatar, frame.avatar_indices),
        ] {
            let (levels, pieces) = looks.levels(key, part);
            self.dynamic_mesh(key, vertices, &levels);
            body_runs.push((key, lod::runs(pieces, vertices, &sight)));
        }
        Detail {
            sight,
            head_level,
            body_runs,
        }
    }

    /// Write the frame's globals (the camera, the lights, the lips' shape,
    /// the shadow's light, redrawn every `shadow_every` frames); true if
    /// the shadow map is to be redrawn this frame.
    fn write_globals(&mut self, frame: &Frame) -> bool {
        let cam = &frame.camera;
        let (key, fill) = (KEY_DIR.normalize(), FILL_DIR.normalize());
        // The shader's plain lighting on the floor's upward normal.
        let floor_light = key_fill_light(Vec3::Y);
        let redo_shadow =
            self.shadow_light.is_none() || self.frames.is_multiple_of(self.shadow_every);
        self.frames += 1;
        if redo_shadow {
            self.shadow_light = Some(shadow_frustum(frame.shadow_focus, self.shadow_size));
        }
        let (light_view_proj, texel) = self.shadow_light.expect("set above");
        let globals = Globals {
            light_view_proj: light_view_proj.to_cols_array_2d(),
            top_dir: TOP_DIR.normalize().extend(0.0).to_array(),
            shadow: [TOP_LIGHT, 1.0, 1.5 * texel, 0.0],
            view_proj: cam.view_proj().to_cols_array_2d(),
            camera: cam.eye.extend(1.0).to_array(),
            key_dir: key.extend(0.0).to_array(),
            fill_dir: fill.extend(0.0).to_array(),
            rim_dir: RIM_DIR.normalize().extend(RIM_LIGHT).to_array(),
            floor_light: [floor_light, 0.0, 0.0, 0.0],
            lips: {
                let l = &frame.lips;
                [
                    [l.half_w, l.mouth_y, l.top, l.bottom],
                    [l.front_z, 0.0, 0.0, 0.0],
                ]
            },
            face_regions: {
                let s = &shisen_face::appearance::FaceStyle::DEFAULT;
                [s.lips, s.brow, s.hair, s.inside].map(|c| [c[0], c[1], c[2], 1.0])
            },
        };
        self.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        redo_shadow
    }

    /// Write each draw's uniforms at its dynamic offset, and the overlays'
    /// lines.
    fn write_instances(&mut self, frame: &Frame) {
        let mut bytes = vec![0u8; frame.draws.len() * INSTANCE_STRIDE as usize];
        for (d, chunk) in frame
            .draws
            .iter()
            .zip(bytes.chunks_mut(INSTANCE_STRIDE as usize))
        {
            let normal = Mat4::from_mat3(Mat3::from_mat4(d.model).inverse().transpose());
            let inst = Instance {
                model: d.model.to_cols_array_2d(),
                normal: normal.to_cols_array_2d(),
                color: d.color,
                params: [d.material as u32 as f32, 0.0, 0.0, 0.0],
            };
            chunk[..size_of::<Instance>()].copy_from_slice(bytemuck::bytes_of(&inst));
        }
        if self.instances.reserve(&self.device, bytes.len() as u64) {
            self.instance_bind = bind(
                &self.device,
                &self.instance_layout,
                &self.instances.buffer,
                size_of::<Instance>() as u64,
            );
        }
        self.queue.write_buffer(&self.instances.buffer, 0, &bytes);
        let line_bytes: &[u8] = bytemuck::cast_slice(&frame.lines);
        self.lines.reserve(&self.device, line_bytes.len() as u64);
        if !line_bytes.is_empty() {
            self.queue.write_buffer(&self.lines.buffer, 0, line_bytes);
        }
    }

    /// Draw the shadow casters' depth from the top light into the shadow
    /// map.
    fn shadow_pass(&self, enc: &mut wgpu::CommandEncoder, frame: &Frame) {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("shisen shadow"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.shadow_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.shadow_pipeline);
        pass.set_bind_group(0, &self.shadow_globals_bind, &[]);
        for (i, d) in frame.draws.iter().enumerate() {
            if !d.material.casts(d.mesh) {
                continue;
            }
            let Some((vertices, indices, count)) = self.caster(d.mesh) else {
                continue;
            };
            pass.set_bind_group(
                1,
                &self.instance_bind,
                &[(i as u64 * INSTANCE_STRIDE) as u32],
            );
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..count, 0, 0..1);
        }
    }

    /// Draw the scene into the target: every draw at its level of detail,
    /// then the overlays' lines over everything.
    fn scene_pass(&self, enc: &mut wgpu::CommandEncoder, frame: &Frame, detail: &Detail) {
        let target = self.target.as_ref().expect("ensured");
        let Detail {
            sight,
            head_level,
            body_runs,
        } = detail;
        let line_bytes: &[u8] = bytemuck::cast_slice(&frame.lines);
        let (view, resolve) = match &target.msaa_view {
            Some(m) => (m, Some(&target.color_view)),
            None => (&target.color_view, None),
        };
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("shisen scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: resolve,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(CLEAR),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.globals_bind, &[]);
        for (i, d) in frame.draws.iter().enumerate() {
            let key = match d.mesh {
                MeshKey::Sphere if sight.coarse_sphere(d.model) => MeshKey::Blob,
                key => key,
            };
            let Some(mesh) = self.mesh_of(key) else {
                continue;
            };
            // The skinned bodies are closed (their keys are dynamic).
            let closed = d.mesh.is_closed() || d.material == Material::Body;
            pass.set_pipeline(&self.pipelines[&(d.material, closed)]);
            pass.set_bind_group(
                1,
                &self.instance_bind,
                &[(i as u64 * INSTANCE_STRIDE) as u32],
            );
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            let runs = body_runs.iter().find(|(k, _)| *k == d.mesh);
            let Some((_, runs)) = runs else {
                let level = match d.mesh {
                    MeshKey::Face | MeshKey::HairShell => *head_level,
                    _ => 0,
                };
                let Some((indices, count)) = mesh.level(level) else {
                    continue;
                };
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..count, 0, 0..1);
                continue;
            };
            for run in runs {
                let Some((indices, _)) = mesh.level(run.level) else {
                    continue;
                };
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(run.range.clone(), 0, 0..1);
            }
        }
        if !frame.lines.is_empty() {
            pass.set_pipeline(&self.line_pipeline);
            pass.set_bind_group(1, &self.instance_bind, &[0]);
            pass.set_vertex_buffer(0, self.lines.buffer.slice(..line_bytes.len() as u64));
            pass.draw(0..frame.lines.len() as u32, 0..1);
        }
    }
}

/// A sphere round `points`: the centre of their box and the farthest
/// point's distance from it.
fn bounding_sphere(points: &[Vec3]) -> (Vec3, f32) {
    let (min, max) = points
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(a, b), p| (a.min(*p), b.max(*p)));
    let centre = (min + max) / 2.0;
    let radius = points
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0, f32::max);
    (centre, radius)
}

/// The top light's view and orthographic projection over a sphere of
/// `focus` (centre, radius), snapped to whole texels of a `size`-texel map
/// so the shadows do not shimmer as the fighters move; and the world size
/// of a texel.
fn shadow_frustum((centre, radius): (Vec3, f32), size: u32) -> (Mat4, f32) {
    let dir = TOP_DIR.normalize();
    let view = glam::camera::rh::view::look_at_mat4(Vec3::ZERO, dir, Vec3::Z);
    let texel = 2.0 * radius / size as f32;
    let c = view.transform_point3(centre);
    let snap = |v: f32| (v / texel).round() * texel;
    let (x, y) = (snap(c.x), snap(c.y));
    // The light looks down -Z of its view: the near plane well above the
    // rig, the far plane below the hall's floor.
    let proj = glam::camera::rh::proj::directx::orthographic(
        x - radius,
        x + radius,
        y - radius,
        y + radius,
        -c.z - 12.0,
        -c.z + 6.0,
    );
    (proj * view, texel)
}
