// Light on a wisp, as on a tube seen side on. A wisp stands for a clump of hair; across its
// width the clump is treated as a cylinder around the strand's 3D tangent T (Costigan 2013
// renders each clump as a swept tube). With V the unit vector towards the eye,
//   B = normalize(V x T)                 the lateral axis; it projects onto the wisp's on-screen
//                                        Left side (Side::Left, u = +1) for a look-at camera
//                                        (image x right, y down)
//   C = normalize(V - (V.T) T)           the part of the view vector across the strand
//   N(u) = u B + sqrt(1 - u^2) C,  u in [-1, 1]
// Under orthographic projection the screen offset of N(u) from the centre line is linear in u,
// so u is the lateral coordinate of the wisp: u = +-1 on its outline, where N is perpendicular to
// V (the tube's silhouette), and 0 on its centre line.
//
// Terms (each in [0, 1]):
//  - Kajiya-Kay diffuse sin(T, L) = sqrt(1 - (T.L)^2) (Kajiya and Kay 1989; Sheppard 2004 uses
//    its square), independent of u;
//  - Lambert fill max(N(u).L, 0): Sheppard found pure anisotropic lighting too dark on hair that
//    points at the light; on the tube it is what moves the lit side across the wisp;
//  - Kajiya-Kay specular sin(T, H)^n with H = normalize(L + V), peaking where T is perpendicular
//    to H (Sheppard's (1 - (T.H)^2)^n is the same with exponent 2n);
//  - Blinn on the tube (N(u).H)^c (Costigan's custom specular): a band across the wisp whose
//    peak along the strand is the Kajiya-Kay peak, sqrt(1 - (T.H)^2) being max_u N(u).H;
//  - Costigan's depth detail D = 1 - log(z / z_near) / log(z_far / z_near), and his back light
//    |N.V|^r (X-Toon metrics, Barla et al. 2006).
// Sheppard's mix: intensity = ambient + S (k_d sin(T, L) + k_l max(N.L, 0)), plus k_s times the
// specular, S his object-over-hair shadow from the head's normal (the only term that tells the
// lit side of the head from the other when strands hang across the light); the toon ramp's x is
// the intensity divided by its maximum, ambient + k_d + k_l.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace wisp::vector {

// The weights of Sheppard's mix (his appendix: ambient 0.2, diffuse 0.35, fill 0.2, specular
// 0.25, exponent 50) and the exponents of the other terms.
struct Lighting {
  double ambient = 0.2;
  double kajiya_diffuse = 0.35;
  double lambert = 0.2;
  double specular = 0.25;    // weight of the smooth Kajiya-Kay specular added to the colour
  double shininess = 50;     // Kajiya-Kay specular exponent n
  double back_exponent = 1;  // r of the back-light metric |N.V|^r
  // Sheppard's object-over-hair shadow S = clamp(L.N_head + head_offset, 0, 1), N_head the
  // outward normal of the head at the strand: hair on the far side of the head from the light is
  // in its shadow. It scales the diffuse terms by 1 - head_shadow (1 - S).
  double head_shadow = 1.0;
  double head_offset = 0.5;
};

struct TubeFrame {
  Eigen::Vector3d T, V, B, C;
};

// T: unit tangent; to_eye: unit vector from the point to the eye. When T is parallel to the
// view (a strand pointing at the camera) the frame is completed with any perpendicular B.
TubeFrame tube_frame(const Eigen::Vector3d& T, const Eigen::Vector3d& to_eye);

// N(u) = u B + sqrt(1 - u^2) C, u clamped to [-1, 1].
Eigen::Vector3d tube_normal(const TubeFrame& f, double u);

double kajiya_kay_diffuse(const Eigen::Vector3d& T, const Eigen::Vector3d& L);
// sin(T, H)^n with H = normalize(L + V); 0 when L = -V.
double kajiya_kay_specular(const Eigen::Vector3d& T, const Eigen::Vector3d& L,
                           const Eigen::Vector3d& V, double n);
// (max(N.H, 0))^c.
double blinn(const Eigen::Vector3d& N, const Eigen::Vector3d& L, const Eigen::Vector3d& V,
             double c);
// Costigan's depth metric, clamped to [0, 1]; 1 at z_near and nearer.
double depth_detail(double z, double z_near, double z_far);
// |N.V|^r.
double back_light(const Eigen::Vector3d& N, const Eigen::Vector3d& V, double r);

// The head's shadow factor 1 - head_shadow (1 - clamp(L.N_head + head_offset, 0, 1)).
double head_shadow(const Eigen::Vector3d& head_normal, const Eigen::Vector3d& L, const Lighting& m);

// Sheppard's intensity (without specular) at lateral coordinate u, and its maximum:
// ambient + shadow (k_d sin(T, L) + k_l max(N(u).L, 0)), `shadow` from head_shadow().
double intensity(const TubeFrame& f, double u, const Eigen::Vector3d& L, const Lighting& m,
                 double shadow = 1.0);
double max_intensity(const Lighting& m);

// Closed form on the tube: with a = B.L, b = C.L and R = sqrt(a^2 + b^2),
// N(u).L = R cos(theta - phi) for u = sin(theta), phi = atan2(a, b). The lateral coordinates
// where N(u).L = k (none when |k| > R; ascending) and where it peaks (u = a / R).
std::vector<double> lambert_iso_u(const TubeFrame& f, const Eigen::Vector3d& L, double k);
double lambert_peak_u(const TubeFrame& f, const Eigen::Vector3d& L);

}  // namespace wisp::vector
