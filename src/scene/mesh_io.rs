//! Mesh files: Wavefront OBJ, STL, Collada. (In progress.)
