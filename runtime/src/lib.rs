//! Patina's runtime: the wgpu renderer, meshes, cameras, scenes, images and the CPU reference
//! rasterizer that the GPU output is measured against.

#![warn(missing_docs)]

pub mod camera;
pub mod corpus;
pub mod gpu;
pub mod image;
pub mod kernel;
pub mod mesh;
pub mod raster;
pub mod render;
pub mod scene;
pub mod stability;
pub mod sweep;
