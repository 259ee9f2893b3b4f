//! Bind groups of buffers in binding order, in the style of Bevy's
//! `BindGroupLayoutEntries::sequential`: binding i is the i-th entry, so a layout and
//! its groups are each written as one list.

/// What a binding of a buffer is.
#[derive(Clone, Copy, Debug)]
pub enum Binding {
    Uniform,
    ReadOnly,
    ReadWrite,
}

impl Binding {
    fn ty(self) -> wgpu::BufferBindingType {
        match self {
            Binding::Uniform => wgpu::BufferBindingType::Uniform,
            Binding::ReadOnly => wgpu::BufferBindingType::Storage { read_only: true },
            Binding::ReadWrite => wgpu::BufferBindingType::Storage { read_only: false },
        }
    }

    /// How many of `bindings` are storage buffers.
    pub const fn storage_buffers(bindings: &[Binding]) -> u32 {
        let (mut i, mut count) = (0, 0);
        while i < bindings.len() {
            count += !matches!(bindings[i], Binding::Uniform) as u32;
            i += 1;
        }
        count
    }

    /// The address space WGSL declares such a binding in.
    pub fn wgsl_address_space(self) -> &'static str {
        match self {
            Binding::Uniform => "uniform",
            Binding::ReadOnly => "storage, read",
            Binding::ReadWrite => "storage, read_write",
        }
    }
}

/// A layout whose binding i is `bindings[i]`, seen by `visibility`.
pub fn sequential_layout(
    device: &wgpu::Device,
    label: &str,
    visibility: wgpu::ShaderStages,
    bindings: &[Binding],
) -> wgpu::BindGroupLayout {
    let entries: Vec<_> = bindings
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupLayoutEntry {
            binding: i as u32,
            visibility,
            ty: wgpu::BindingType::Buffer { ty: b.ty(), has_dynamic_offset: false, min_binding_size: None },
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries })
}

/// A group whose binding i is the whole of `buffers[i]`.
pub fn bind_group(
    ctx: &super::GpuContext,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<_> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
        .collect();
    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some(label), layout, entries: &entries })
}
