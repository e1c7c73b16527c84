//! The window's picture rendered a frame ahead on a device of its own.
//!
//! On a software rasteriser (lavapipe) a device's queue runs its work in
//! order: the 3D view's binning, then its rasterising, then the window's
//! pass (the blit and egui's text), then presenting, and a second
//! submission waits for the first to finish. Presenting to an X server
//! without shared memory (Xvfb) sends the picture down the socket, and the
//! toolkit's next requests wait for the server to have taken it in. Drawn
//! on the window's own device, each step waited for the one before, and a
//! quarter of two cores stood idle in a frame (`perf record -a`). Drawn on
//! a device of its own (of an instance of its own, which has its own
//! rasteriser threads), the view of one frame is rasterised while the
//! window's device copies the view of the frame before into the window
//! and presents it: the chain becomes two that overlap. The picture crosses between the
//! devices through the CPU (read back into a mapped buffer, written into
//! a texture of the window's device: a few copies of under a megabyte at
//! the window's usual render scale). The cost is one frame of latency:
//! the window shows the view of the previous step.

use shisen_face::mesh::HeadMesh;

use super::frame::Frame;
use super::gpu::{COLOR_FORMAT, COLOR_FORMAT_UNORM, RenderError, Renderer};

/// Two read-back buffers (one being filled by the renderer's device while
/// the other's picture is handed over) and the texture on the window's
/// device that holds the picture handed over last.
pub struct Relay {
    /// The window's device and queue.
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// Read-back buffers by frame parity, each with the picture size it
    /// holds and whether a picture is on its way into it.
    slots: [Option<Slot>; 2],
    /// Frames sent.
    sent: u64,
    /// The picture on the window's device.
    shown: Option<(wgpu::Texture, (u32, u32))>,
}

struct Slot {
    buffer: wgpu::Buffer,
    size: (u32, u32),
    padded_row: u32,
    /// A copy into it was submitted (index on the renderer's queue) and
    /// its mapping requested.
    pending: Option<wgpu::SubmissionIndex>,
}

impl Relay {
    /// A renderer for a window on `adapter`'s `device` and `queue`, on a
    /// device of its own, and the relay that hands its pictures to the
    /// window. The device comes from an instance of its own: lavapipe
    /// shares one set of rasteriser threads between the devices of an
    /// instance, and a second device of the same instance only queues
    /// behind the first. The adapter is the one of the same name and type
    /// as the window's.
    pub fn open(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<(Renderer, Relay), RenderError> {
        let wanted = adapter.get_info();
        let backends = wgpu::Backends::from(wanted.backend);
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        desc.backends = backends;
        let instance = wgpu::Instance::new(desc);
        let own = pollster::block_on(instance.enumerate_adapters(backends))
            .into_iter()
            .find(|a| {
                let info = a.get_info();
                info.name == wanted.name && info.device_type == wanted.device_type
            })
            .ok_or_else(|| {
                RenderError::NoAdapter(format!("a second instance has no {}", wanted.name))
            })?;
        let (own_device, own_queue) =
            pollster::block_on(own.request_device(&wgpu::DeviceDescriptor {
                label: Some("shisen view"),
                required_limits: wgpu::Limits::downlevel_defaults().using_resolution(own.limits()),
                ..Default::default()
            }))?;
        let relay = Relay {
            device: device.clone(),
            queue: queue.clone(),
            slots: [None, None],
            sent: 0,
            shown: None,
        };
        Ok((Renderer::for_window(&own, &own_device, &own_queue), relay))
    }

    /// Render `frame` with `renderer` (on its own device) at `size`, and
    /// start copying the picture back to the CPU in the same submission
    /// (it reaches the window with [`Relay::receive`] a frame later).
    pub fn render(
        &mut self,
        renderer: &mut Renderer,
        frame: &Frame,
        face: &HeadMesh,
        size: (u32, u32),
    ) {
        let slot = &mut self.slots[(self.sent % 2) as usize];
        if slot
            .as_ref()
            .is_none_or(|s| s.size != size || s.pending.is_some())
        {
            let padded_row = (size.0 * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
                * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
            *slot = Some(Slot {
                buffer: renderer.device().create_buffer(&wgpu::BufferDescriptor {
                    label: Some("shisen relay"),
                    size: u64::from(padded_row) * u64::from(size.1),
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                size,
                padded_row,
                pending: None,
            });
        }
        let Some(slot) = slot.as_mut() else {
            return;
        };
        let index = renderer.render_then(frame, face, size, |enc, color| {
            enc.copy_texture_to_buffer(
                color.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &slot.buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(slot.padded_row),
                        rows_per_image: Some(size.1),
                    },
                },
                wgpu::Extent3d {
                    width: size.0,
                    height: size.1,
                    depth_or_array_layers: 1,
                },
            );
        });
        slot.buffer.slice(..).map_async(wgpu::MapMode::Read, |_| ());
        slot.pending = Some(index);
        self.sent += 1;
    }

    /// Hand the picture rendered the frame before the last
    /// [`Relay::render`] to the window's device ([`Relay::shown`] from
    /// then on), waiting for the renderer's device to finish it (which it
    /// has in the usual case). Nothing before the second frame. On an
    /// error that picture is dropped, its buffer with it, and the one
    /// before stays shown.
    pub fn receive(&mut self, renderer: &Renderer) -> Result<(), RenderError> {
        let k = (self.sent % 2) as usize;
        let Some(slot) = self.slots[k].as_mut() else {
            return Ok(());
        };
        let Some(index) = slot.pending.take() else {
            return Ok(());
        };
        let handed = hand_over(
            &self.device,
            &self.queue,
            &mut self.shown,
            slot,
            renderer,
            index,
        );
        match handed {
            Ok(()) => slot.buffer.unmap(),
            Err(_) => self.slots[k] = None,
        }
        handed
    }

    /// The picture handed over last, on the window's device.
    pub fn shown(&self) -> Option<&wgpu::Texture> {
        self.shown.as_ref().map(|(t, _)| t)
    }
}

/// Wait for `slot`'s picture (submission `index` of `renderer`'s device)
/// and write it into `shown` on the window's `device` (a new texture when
/// its size changed).
fn hand_over(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    shown: &mut Option<(wgpu::Texture, (u32, u32))>,
    slot: &Slot,
    renderer: &Renderer,
    index: wgpu::SubmissionIndex,
) -> Result<(), RenderError> {
    renderer
        .device()
        .poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: None,
        })
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let extent = wgpu::Extent3d {
        width: slot.size.0,
        height: slot.size.1,
        depth_or_array_layers: 1,
    };
    if shown.as_ref().is_none_or(|(_, s)| *s != slot.size) {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shisen relayed picture"),
            size: extent,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: COLOR_FORMAT,
            usage: wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[COLOR_FORMAT_UNORM],
        });
        *shown = Some((texture, slot.size));
    }
    let Some((texture, _)) = shown else {
        return Ok(());
    };
    let data = slot
        .buffer
        .slice(..)
        .get_mapped_range()
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    queue.write_texture(
        texture.as_image_copy(),
        &data,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(slot.padded_row),
            rows_per_image: Some(slot.size.1),
        },
        extent,
    );
    Ok(())
}
