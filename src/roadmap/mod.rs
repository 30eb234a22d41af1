//! The roadmap: learning, persistence, queries. (In progress.)
