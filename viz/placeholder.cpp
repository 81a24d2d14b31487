// Keeps this library non-empty until its first real file lands; delete it then.
namespace fovea { int vizPlaceholder() { return 0; } }
