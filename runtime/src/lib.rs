//! The runtime arrives with issue 6 (wgpu device, pipelines, scenes, the CPU reference renderer).
