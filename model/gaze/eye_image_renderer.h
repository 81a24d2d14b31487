#pragma once
// Synthetic IR eye-camera images with ground truth: what a headset's eye camera sees of the
// eye model, deterministic by seed, for the pupil detector's tests and benchmark and for
// the virtual bench's eye camera.
//
// Geometry (eye frame = bench axes at the eye's rotation centre; zero gaze looks along +z,
// gazeDirection of scene_geometry.h): the pupil is a disc of the scene's diameter, normal to
// the gaze, `pupil_distance_mm` from the rotation centre; the iris a coplanar annulus out
// to `iris_radius_mm`; the cornea a sphere of radius `cornea_radius_mm` whose apex lies
// `anterior_chamber_mm` in front of the pupil plane (Le Grand eye: r = 7.8 mm, 3.6 mm).
// Refraction at the cornea is ignored by default (it magnifies the pupil by ~1.13 and
// shifts it a little, a smooth map the gaze calibration absorbs); with corneal_refraction
// the pupil and iris are drawn as their images through the corneal sphere (the entrance
// pupil, paraxial; see eye_image_renderer.cpp). The pinhole camera sits
// `distance_mm` from the rotation centre in the direction (yaw, pitch) of the camera pose
// and looks at the rotation centre; image x follows bench +x, image y bench -y.
//
// Appearance (0..1 radiance, 8-bit on output): skin around an almond-shaped lid opening,
// sclera, an iris with radial crypt texture, a dark pupil (IR dark-pupil illumination),
// corneal glints (first Purkinje images) of point IR LEDs where the corneal normal bisects
// the directions to the LED and to the camera (the far-source approximation), eyelashes on
// the upper lid, eyelids whose upper edge may cover part of the pupil (openness 0 closes
// the eye), a saccade during the exposure (sub-frames averaged: motion blur), defocus
// (Gaussian), and Gaussian sensor noise.
//
// Ground truth: the pupil outline projected at mid-exposure and fitted by an ellipse (the
// perspective image of a circle is an ellipse; 64 projected outline points fix it to
// well under 0.1 px), its visible fraction (not under the lids) and the glint positions.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace fovea::gaze {

struct IrCameraPose {
  double focal_px = 350;
  cv::Size size{400, 400};
  double distance_mm = 35;               // rotation centre to pinhole
  std::array<double, 2> pose_deg{0, 0};  // camera direction seen from the eye (yaw, pitch); headsets: ~(15, -25)
  std::array<double, 2> principal_offset_px{0, 0};  // principal point from the image centre (a shifted sensor window)
};

struct EyeAppearance {
  double pupil_diameter_mm = 5.0;
  double pupil_distance_mm = 10.0;  // rotation centre to pupil plane
  double iris_radius_mm = 6.0;
  double cornea_radius_mm = 7.8;
  double anterior_chamber_mm = 3.6;
  double lid_half_width_mm = 15;  // half the palpebral fissure, in the plane of the pupil at zero gaze
  double lid_half_height_mm = 6;  // fully open: upper and lower lid edges above/below the centre
  double openness = 1.0;          // 1 open, 0 closed (the upper lid drops to the lower one)
  double pupil_level = 0.08, iris_level = 0.42, sclera_level = 0.78, skin_level = 0.62;
  int eyelashes = 40;
  bool corneal_refraction = false;  // draw the entrance pupil (image through the cornea)
  double aqueous_index = 1.3375;    // Le Grand eye: aqueous and cornea as one medium
};

struct EyeFrameSpec {
  std::array<double, 2> gaze_deg{0, 0};      // at the start of the exposure
  std::array<double, 2> gaze_end_deg{0, 0};  // at the end (differs during a saccade: motion blur)
  bool moving = false;                       // use gaze_end_deg
  std::vector<Eigen::Vector3d> leds_mm;      // IR LED positions in the eye frame (glints)
  double defocus_sigma_px = 0.8;
  double noise_sigma = 0.02;  // radiance units (x255 DN)
  int blur_subframes = 8;
  std::uint32_t seed = 1;  // texture, lashes and noise
};

struct EyeEllipse {
  cv::Point2d centre{0, 0};
  double major_px = 0, minor_px = 0;  // full axes (diameters)
  double angle_deg = 0;               // of the major axis, image x towards image y
};

struct EyeFrameTruth {
  bool pupil_visible = false;            // some of the pupil shows between the lids
  double visible_fraction = 0;           // of the pupil's image area
  EyeEllipse pupil;                      // full (unoccluded) outline at mid-exposure
  std::array<double, 2> gaze_deg{0, 0};  // at mid-exposure
  std::vector<cv::Point2d> glints_px;    // those that fall on the visible cornea
};

struct EyeFrame {
  cv::Mat image;  // CV_8U
  EyeFrameTruth truth;
};

// A ring of `count` LEDs around the camera (radius_mm from its axis, in its image plane),
// as on a headset's eye-tracking ring.
std::vector<Eigen::Vector3d> ledRing(const IrCameraPose& camera, int count, double radius_mm);

// Image (px) of a point of the eye frame; NaN for a point behind the camera.
std::array<double, 2> projectToCamera(const IrCameraPose& camera, const Eigen::Vector3d& point_mm);

EyeFrame renderEyeFrame(const IrCameraPose& camera, const EyeAppearance& eye, const EyeFrameSpec& spec);
// The ground truth alone (what renderEyeFrame returns in .truth), without drawing the image.
EyeFrameTruth eyeFrameTruth(const IrCameraPose& camera, const EyeAppearance& eye, const EyeFrameSpec& spec);

}  // namespace fovea::gaze
