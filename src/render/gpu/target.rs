//! The picture a frame is drawn into, and reading it back to the CPU.

use super::{COLOR_FORMAT, COLOR_FORMAT_UNORM, DEPTH_FORMAT, RenderError, Renderer};

/// The picture drawn into: its resolved colour texture, the
/// multisampled one (if any) and the depth buffer, at `size` pixels.
pub(super) struct Target {
    pub(super) size: (u32, u32),
    pub(super) color: wgpu::Texture,
    pub(super) color_view: wgpu::TextureView,
    pub(super) msaa_view: Option<wgpu::TextureView>,
    pub(super) depth_view: wgpu::TextureView,
}

impl Renderer {
    /// Make the target `size` pixels (kept if it already is).
    pub(super) fn ensure_target(&mut self, size: (u32, u32)) {
        if self.target.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        let extent = wgpu::Extent3d {
            width: size.0.max(1),
            height: size.1.max(1),
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage, view_formats: &[wgpu::TextureFormat]| {
            self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats,
            })
        };
        let attach = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let color = texture(
            "shisen colour",
            COLOR_FORMAT,
            1,
            attach | wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::TEXTURE_BINDING,
            &[COLOR_FORMAT_UNORM],
        );
        let msaa_view = (self.samples > 1).then(|| {
            texture("shisen msaa", COLOR_FORMAT, self.samples, attach, &[])
                .create_view(&Default::default())
        });
        let depth_view = texture("shisen depth", DEPTH_FORMAT, self.samples, attach, &[])
            .create_view(&Default::default());
        self.target = Some(Target {
            size,
            color_view: color.create_view(&Default::default()),
            color,
            msaa_view,
            depth_view,
        });
    }

    /// Copy the last render back to the CPU (blocks until the GPU is done).
    pub fn read_rgba(&self) -> Result<image::RgbaImage, RenderError> {
        let target = self.target.as_ref().ok_or(RenderError::NothingRendered)?;
        self.read_texture(&target.color)
    }

    /// Copy a picture of this renderer's device (in its colour format,
    /// with `COPY_SRC` use) back to the CPU (blocks until the GPU is done).
    pub fn read_texture(&self, texture: &wgpu::Texture) -> Result<image::RgbaImage, RenderError> {
        let (w, h) = (texture.width(), texture.height());
        let row = w * 4;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shisen readback"),
            size: padded as u64 * h as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("shisen readback"),
            });
        enc.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: None,
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([enc.finish()]);
        let slice = buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        rx.recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mut pixels = Vec::with_capacity((row * h) as usize);
        for r in data.chunks(padded as usize) {
            pixels.extend_from_slice(&r[..row as usize]);
        }
        drop(data);
        buffer.unmap();
        image::RgbaImage::from_raw(w, h, pixels)
            .ok_or_else(|| RenderError::Readback("short image".into()))
    }
}
