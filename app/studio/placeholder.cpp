// Keeps fovea_app non-empty until the main window lands.
namespace fovea {
int studioPlaceholder() { return 0; }
}
