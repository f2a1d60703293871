//! Writing fields: one field to every output (`write`), streamed outputs of fields too
//! large for memory (`stream`), batches of jobs (`batch`, `jobs`), previews, and the
//! memory guard. Commands call this layer; it never calls back.

pub mod analysis;
pub mod batch;
pub mod compute;
pub mod foam_fade;
pub mod jobs;
pub mod memory;
pub mod preview;
pub mod reports;
pub mod sequence;
pub mod stream;
pub mod write;
