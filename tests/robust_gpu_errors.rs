//! GPU errors never panic: wgpu's default handler for an error no scope caught panics;
//! rt's records it, and `GpuContext::take_error` (which `wait` calls after every
//! submission it waits for) returns it as an `Err` with the GPU's message.

use crate::common;
use rt::gpu::GpuContext;

/// A buffer usage wgpu refuses: MAP_READ may only go with COPY_DST.
fn invalid_buffer(ctx: &GpuContext) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("invalid on purpose"),
        size: 16,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}

#[test]
fn an_uncaptured_validation_error_becomes_an_err() {
    // A device of this test's own: the errors made on purpose here must not reach the
    // tests that share the binary's device.
    let ctx = &common::new_gpu();
    ctx.take_error().expect("a fresh device has no error");
    let _buffer = invalid_buffer(ctx);
    let message = ctx.take_error().expect_err("the invalid buffer was recorded").to_string();
    assert!(message.starts_with("GPU error: "), "{message}");
    assert!(message.contains("invalid on purpose"), "the message names the resource: {message}");
    ctx.take_error().expect("an error is reported once");

    // Through the wait that follows a submission, as every render loop does.
    let _first = invalid_buffer(ctx);
    let _second = invalid_buffer(ctx);
    ctx.queue.submit([]);
    let message = ctx.wait().expect_err("wait reports the errors").to_string();
    assert!(message.contains("(and 1 more GPU errors)"), "{message}");
    ctx.wait().expect("and then the device is fine");
}
