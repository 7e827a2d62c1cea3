//! Writing a [`Decomposition`](crate::Decomposition) out: SVG documents ([`svg`]).

pub mod svg;
