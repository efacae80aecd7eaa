//! Stream plumbing between the stages: the cameras' register slices and the record queues between the detectors and the matcher.

pub mod skid_buffer;
pub mod record_fifo;
