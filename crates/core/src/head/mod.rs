//! The head being aged: its mesh (OBJ, glTF, UDIM), the default head, its landmarks, the
//! template fitted to it (`fit`), and the face frame every layer draws its regions in
//! (`frame`: the regions, the brows' and lids' places).

pub mod default;
pub mod fit;
pub mod frame;
pub mod landmarks;
pub mod mesh;
