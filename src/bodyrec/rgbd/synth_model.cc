#include "bodyrec/rgbd/synth_model.h"

#include <algorithm>
#include <cmath>

namespace bodyrec::synth {
namespace {

cv::Vec3f bgr(int r, int g, int b) { return {static_cast<float>(b), static_cast<float>(g), static_cast<float>(r)}; }

struct Named {
  const char* name;
  cv::Vec3f colour;
};

// Distinct clothing colours (names go into the truth for re-identification evaluation).
const std::vector<Named>& top_palette() {
  static const std::vector<Named> p = {
      {"red", bgr(200, 30, 35)},     {"blue", bgr(35, 70, 190)},     {"green", bgr(40, 150, 60)},
      {"yellow", bgr(225, 195, 40)}, {"white", bgr(230, 230, 225)},  {"black", bgr(30, 30, 35)},
      {"orange", bgr(235, 120, 30)}, {"purple", bgr(120, 50, 150)},  {"teal", bgr(20, 140, 150)},
      {"pink", bgr(230, 120, 170)},  {"grey", bgr(128, 128, 130)},   {"brown", bgr(120, 75, 40)}};
  return p;
}
const std::vector<Named>& bottom_palette() {
  static const std::vector<Named> p = {{"dark blue", bgr(35, 45, 85)}, {"black", bgr(25, 25, 28)},
                                       {"light blue", bgr(110, 140, 185)}, {"khaki", bgr(170, 150, 105)},
                                       {"grey", bgr(95, 95, 100)},     {"brown", bgr(90, 60, 40)},
                                       {"olive", bgr(85, 95, 45)},     {"white", bgr(215, 215, 210)}};
  return p;
}

cv::Vec3d rot_x_dir(double a, double side) {
  // Unit direction hanging down, swung forward (-Z) by angle a and out sideways by `side` (x).
  cv::Vec3d d(side, -std::cos(a), -std::sin(a));
  return d / cv::norm(d);
}

cv::Matx33d rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c, 0, s, 0, 1, 0, -s, 0, c};
}
cv::Matx33d rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {1, 0, 0, 0, c, -s, 0, s, c};
}
cv::Matx33d rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c, -s, 0, s, c, 0, 0, 0, 1};
}

// Minimal rotation taking unit vector a onto unit vector b (a, b not opposite).
cv::Matx33d align(const cv::Vec3d& a, const cv::Vec3d& b) {
  const cv::Vec3d v = a.cross(b);
  const double c = a.dot(b);
  const cv::Matx33d vx(0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0);
  return cv::Matx33d::eye() + vx + vx * vx * (1.0 / (1.0 + c));
}

Primitive capsule(const cv::Vec3d& a, const cv::Vec3d& b, double r, Material m) {
  Primitive p;
  p.capsule = true;
  p.a = cv::Vec3f(a);
  p.b = cv::Vec3f(b);
  p.r = static_cast<float>(r);
  p.material = m;
  return p;
}

// Ellipsoid centred at c with semi-axes `radii` along the columns of rotation `r`.
Primitive ellipsoid(const cv::Vec3d& c, const cv::Matx33d& r, const cv::Vec3d& radii, Material m) {
  Primitive p;
  p.capsule = false;
  p.a = cv::Vec3f(c);
  p.b = p.a;
  p.r = static_cast<float>(std::max({radii[0], radii[1], radii[2]}));
  const cv::Matx33d inv_s(1 / radii[0], 0, 0, 0, 1 / radii[1], 0, 0, 0, 1 / radii[2]);
  p.m = cv::Matx33f(inv_s * r.t());
  p.material = m;
  return p;
}

}  // namespace

uint32_t hash32(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return static_cast<uint32_t>(x);
}

double uniform(uint64_t seed, uint64_t stream, uint64_t index) {
  return hash32(seed * 0x9E3779B97F4A7C15ULL + stream * 0xBF58476D1CE4E5B9ULL + index) / 4294967296.0;
}

Look make_look(uint64_t seed, int identity, int people) {
  const auto u = [&](int k) { return uniform(seed, 1000 + static_cast<uint64_t>(identity), static_cast<uint64_t>(k)); };
  Look l;
  l.height = 1.55 + 0.40 * u(0);
  l.build = 0.85 + 0.40 * u(1);
  l.shoulder = l.height * (0.215 + 0.03 * u(2)) * (0.9 + 0.1 * l.build);
  l.hips = l.height * (0.16 + 0.03 * u(3)) * (0.9 + 0.1 * l.build);
  const std::vector<cv::Vec3f> skins = {bgr(240, 200, 170), bgr(220, 175, 140), bgr(180, 130, 95),
                                        bgr(140, 95, 65), bgr(95, 65, 45)};
  const std::vector<cv::Vec3f> hairs = {bgr(25, 20, 15), bgr(90, 60, 30), bgr(200, 160, 90), bgr(150, 60, 30),
                                        bgr(170, 170, 165)};
  l.skin = skins[static_cast<size_t>(u(4) * skins.size())];
  l.hair = hairs[static_cast<size_t>(u(5) * hairs.size())];
  // Tops: a seed-shuffled palette, one colour per identity, so people of one recording differ.
  const auto& tops = top_palette();
  std::vector<size_t> order(tops.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (size_t i = order.size() - 1; i > 0; --i)
    std::swap(order[i], order[static_cast<size_t>(uniform(seed, 77, i) * static_cast<double>(i + 1))]);
  const Named& top = tops[order[static_cast<size_t>(identity) % order.size()]];
  const Named& top2 = tops[order[static_cast<size_t>(identity + people + 1) % order.size()]];
  const auto& bottoms = bottom_palette();
  const Named& bottom = bottoms[static_cast<size_t>(u(6) * bottoms.size())];
  l.top = top.colour;
  l.top2 = top2.colour;
  l.bottom = bottom.colour;
  l.bottom2 = bgr(235, 235, 235);
  l.shoes = u(7) < 0.5 ? bgr(30, 30, 30) : bgr(220, 220, 220);
  l.top_pattern = static_cast<int>(u(8) * 4);
  l.bottom_pattern = u(9) < 0.25 ? 1 : 0;
  l.chest_print = u(10) < 0.5;
  l.long_sleeves = u(11) < 0.6;
  l.shorts = u(12) < 0.25;
  l.long_hair = u(13) < 0.4;
  l.has_hat = u(14) < 0.3;
  const double bag = u(15);
  l.backpack = bag < 0.3;
  l.shoulder_bag = bag >= 0.3 && bag < 0.5;
  l.hat = tops[order[static_cast<size_t>(identity + 3) % order.size()]].colour;
  l.bag = u(16) < 0.5 ? bgr(60, 45, 35) : bgr(40, 60, 40);
  static const char* patterns[] = {"", " horizontal-striped", " vertical-striped", " checked"};
  l.top_text = std::string(top.name) + patterns[l.top_pattern] + (l.long_sleeves ? " long-sleeved" : " short-sleeved") +
               " top" + (l.top_pattern ? std::string(" with ") + top2.name : "") + (l.chest_print ? ", chest print" : "");
  l.bottom_text = std::string(bottom.name) + (l.shorts ? " shorts" : " trousers") + (l.bottom_pattern ? " with side stripes" : "");
  if (l.has_hat) l.accessories.push_back("hat");
  if (l.backpack) l.accessories.push_back("backpack");
  if (l.shoulder_bag) l.accessories.push_back("shoulder bag");
  return l;
}

PersonModel build_person(const Look& l, const Pose& pose) {
  PersonModel m;
  const double h = l.height, g = l.build, s = h / 1.75;
  m.body_to_camera = rot_y(pose.yaw);
  m.origin = pose.floor_point;
  // Gait: hips swing +-0.45 rad, knees bend on the swing phase, arms swing against the legs.
  const double a = pose.stride, ph = pose.phase;
  const double hip_l = 0.45 * a * std::sin(ph), hip_r = -hip_l;
  const double knee_l = 0.7 * a * std::max(0.0, std::sin(ph + 1.3)), knee_r = 0.7 * a * std::max(0.0, std::sin(ph + 1.3 + M_PI));
  const double arm_l = -0.4 * a * std::sin(ph), arm_r = -arm_l;
  const double bob = 0.015 * a * std::cos(2 * ph);

  std::array<cv::Vec3d, kJointCount> b;  // body coordinates: x right, y up, z back
  const double pelvis = 0.53 * h + bob;
  const double thigh = 0.245 * h, shin = 0.235 * h, upper = 0.17 * h, fore = 0.15 * h;
  b[idx(Joint::kSpineBase)] = {0, pelvis, 0};
  b[idx(Joint::kSpineMid)] = {0, pelvis + 0.14 * h, 0.01};
  b[idx(Joint::kSpineShoulder)] = {0, pelvis + 0.29 * h, 0.0};
  b[idx(Joint::kNeck)] = {0, pelvis + 0.32 * h, -0.005};
  m.head_radii = cv::Vec3d(0.078, 0.11, 0.095) * s;
  m.head_centre = {0, h - m.head_radii[1] + bob, -0.01};
  b[idx(Joint::kHead)] = m.head_centre;
  for (int side = -1; side <= 1; side += 2) {  // -1 left, +1 right
    const bool left = side < 0;
    const double hip_a = left ? hip_l : hip_r, knee = left ? knee_l : knee_r, arm = left ? arm_l : arm_r;
    const Joint sh = left ? Joint::kShoulderLeft : Joint::kShoulderRight, el = left ? Joint::kElbowLeft : Joint::kElbowRight,
                wr = left ? Joint::kWristLeft : Joint::kWristRight, ha = left ? Joint::kHandLeft : Joint::kHandRight,
                tip = left ? Joint::kHandTipLeft : Joint::kHandTipRight, th = left ? Joint::kThumbLeft : Joint::kThumbRight,
                hp = left ? Joint::kHipLeft : Joint::kHipRight, kn = left ? Joint::kKneeLeft : Joint::kKneeRight,
                an = left ? Joint::kAnkleLeft : Joint::kAnkleRight, ft = left ? Joint::kFootLeft : Joint::kFootRight;
    b[idx(sh)] = b[idx(Joint::kSpineShoulder)] + cv::Vec3d(side * l.shoulder / 2, -0.02 * h, 0.01);
    b[idx(el)] = b[idx(sh)] + upper * rot_x_dir(arm, side * 0.12);
    b[idx(wr)] = b[idx(el)] + fore * rot_x_dir(arm + 0.25 + 0.3 * a, side * 0.05);
    b[idx(ha)] = b[idx(wr)] + 0.04 * h * rot_x_dir(arm + 0.3, 0);
    b[idx(tip)] = b[idx(ha)] + 0.045 * h * rot_x_dir(arm + 0.3, 0);
    b[idx(th)] = b[idx(wr)] + 0.035 * h * rot_x_dir(arm + 0.6, -side * 0.6);
    b[idx(hp)] = b[idx(Joint::kSpineBase)] + cv::Vec3d(side * l.hips / 2 * 0.6, -0.03 * h, 0);
    b[idx(kn)] = b[idx(hp)] + thigh * rot_x_dir(hip_a, side * 0.03);
    b[idx(an)] = b[idx(kn)] + shin * rot_x_dir(hip_a - knee, 0);
    b[idx(ft)] = b[idx(an)] + cv::Vec3d(0, -0.035 * h, -0.10 * h);
  }
  // Keep the lower foot on the floor.
  const double lowest = std::min(b[idx(Joint::kAnkleLeft)][1], b[idx(Joint::kAnkleRight)][1]) - 0.045 * h;
  for (auto& p : b) p[1] -= lowest;
  m.head_centre[1] -= lowest;

  const cv::Matx33d& r = m.body_to_camera;
  for (int j = 0; j < kJointCount; ++j) m.joints[static_cast<size_t>(j)] = m.origin + r * b[static_cast<size_t>(j)];

  // Orientations: the body rotation turned so its Y axis runs along the bone from the parent (Kinect
  // style). Rest directions avoid the degenerate half-turn: spine up, shoulders out, limbs down.
  // Kinect's joint frames have Z along the body's forward direction (checked on NTU RGB+D: a body facing
  // the sensor holds about R_y(180 deg)); body coordinates here have z back, hence the half turn.
  const cv::Matx33d to_kinect = rot_y(M_PI);
  m.orientations[idx(Joint::kSpineBase)] = Quaternion::from_matrix(r * to_kinect);
  for (int j = 1; j < kJointCount; ++j) {
    const Joint jt = static_cast<Joint>(j);
    if (jt == Joint::kHead || jt == Joint::kFootLeft || jt == Joint::kFootRight || jt == Joint::kHandTipLeft ||
        jt == Joint::kHandTipRight || jt == Joint::kThumbLeft || jt == Joint::kThumbRight)
      continue;  // end joints: none, as on Kinect
    cv::Vec3d bone = b[static_cast<size_t>(j)] - b[static_cast<size_t>(joint_parent(j))];
    bone /= cv::norm(bone);
    cv::Matx33d rest = cv::Matx33d::eye();
    if (jt == Joint::kShoulderLeft) rest = rot_z(M_PI / 2);
    else if (jt == Joint::kShoulderRight) rest = rot_z(-M_PI / 2);
    else if (jt == Joint::kHipLeft) rest = rot_z(M_PI / 2);
    else if (jt == Joint::kHipRight) rest = rot_z(-M_PI / 2);
    else if (bone[1] < 0) rest = rot_x(M_PI);
    const cv::Vec3d rest_dir(rest(0, 1), rest(1, 1), rest(2, 1));
    m.orientations[static_cast<size_t>(j)] = Quaternion::from_matrix(r * align(rest_dir, bone) * rest * to_kinect);
  }

  // Dress the skeleton. Body coordinates -> camera via `to`.
  const auto to = [&](const cv::Vec3d& p) { return m.origin + r * p; };
  const auto J = [&](Joint j) { return m.joints[static_cast<size_t>(idx(j))]; };
  auto& P = m.primitives;
  const double chest_y = b[idx(Joint::kSpineShoulder)][1] - 0.11 * h;
  P.push_back(ellipsoid(to({0, chest_y, 0.01}), r, cv::Vec3d(l.shoulder * 0.47, 0.15 * h, 0.10 * g * s), Material::kTop));
  P.push_back(ellipsoid(to({0, b[idx(Joint::kSpineMid)][1] - 0.02 * h, 0.01}), r,
                        cv::Vec3d(l.hips * 0.52 + 0.02 * g, 0.11 * h, 0.095 * g * s), Material::kTop));
  P.push_back(ellipsoid(to({0, b[idx(Joint::kSpineBase)][1] - 0.01 * h, 0.0}), r,
                        cv::Vec3d(l.hips * 0.55, 0.075 * h, 0.095 * g * s), Material::kBottom));
  P.push_back(capsule(J(Joint::kSpineShoulder), J(Joint::kNeck) + r * cv::Vec3d(0, 0.03 * h, 0), 0.05 * s, Material::kSkin));
  P.push_back(ellipsoid(to(m.head_centre), r, m.head_radii, Material::kHead));
  for (int side = 0; side < 2; ++side) {
    const bool left = side == 0;
    const Joint sh = left ? Joint::kShoulderLeft : Joint::kShoulderRight, el = left ? Joint::kElbowLeft : Joint::kElbowRight,
                wr = left ? Joint::kWristLeft : Joint::kWristRight, ha = left ? Joint::kHandLeft : Joint::kHandRight,
                hp = left ? Joint::kHipLeft : Joint::kHipRight, kn = left ? Joint::kKneeLeft : Joint::kKneeRight,
                an = left ? Joint::kAnkleLeft : Joint::kAnkleRight, ft = left ? Joint::kFootLeft : Joint::kFootRight;
    P.push_back(capsule(J(sh), J(el), 0.047 * g * s, Material::kTop));
    P.push_back(capsule(J(el), J(wr), 0.038 * g * s, l.long_sleeves ? Material::kTop : Material::kSkin));
    P.push_back(capsule(J(wr), J(ha), 0.036 * s, Material::kSkin));
    P.push_back(capsule(J(hp), J(kn), 0.074 * g * s, Material::kBottom));
    const cv::Vec3d knee = J(kn), ankle = J(an);
    if (l.shorts) {
      const cv::Vec3d mid = knee + (ankle - knee) * 0.15;
      P.push_back(capsule(knee, mid, 0.062 * g * s, Material::kBottom));
      P.push_back(capsule(mid, ankle, 0.05 * g * s, Material::kSkin));
    } else {
      P.push_back(capsule(knee, ankle, 0.058 * g * s, Material::kBottom));
    }
    P.push_back(capsule(ankle + r * cv::Vec3d(0, -0.02 * h, 0.03 * s), J(ft) + r * cv::Vec3d(0, 0.015 * h, 0), 0.042 * s,
                        Material::kShoes));
  }
  const cv::Vec3d hc = m.head_centre, hr = m.head_radii;
  if (l.has_hat) {
    P.push_back(ellipsoid(to(hc + cv::Vec3d(0, hr[1] * 0.55, 0)), r, cv::Vec3d(hr[0] * 1.55, 0.018 * s, hr[2] * 1.55),
                          Material::kHat));
    P.push_back(ellipsoid(to(hc + cv::Vec3d(0, hr[1] * 0.65, 0)), r, cv::Vec3d(hr[0] * 1.02, hr[1] * 0.5, hr[2] * 1.02),
                          Material::kHat));
  }
  if (l.backpack)
    P.push_back(ellipsoid(to({0, chest_y - 0.03 * h, 0.10 * g * s + 0.08}), r, cv::Vec3d(0.15, 0.20, 0.08) * s, Material::kBag));
  if (l.shoulder_bag) {
    const cv::Vec3d bag = {-(l.hips * 0.55 + 0.06), b[idx(Joint::kSpineBase)][1] + 0.02 * h, 0.0};
    P.push_back(ellipsoid(to(bag), r, cv::Vec3d(0.05, 0.12, 0.15) * s, Material::kBag));
    P.push_back(capsule(J(Joint::kShoulderRight) + r * cv::Vec3d(-0.03, 0.02, 0), to(bag + cv::Vec3d(0, 0.1 * s, 0)), 0.012,
                        Material::kBag));
  }
  return m;
}

cv::Vec3f shade(const Look& l, const PersonModel& m, Material mat, const cv::Vec3f& p, const cv::Vec3f& n) {
  const cv::Vec3d q = m.body_to_camera.t() * (cv::Vec3d(p) - m.origin);  // body coordinates
  cv::Vec3f c;
  switch (mat) {
    case Material::kSkin: c = l.skin; break;
    case Material::kShoes: c = l.shoes; break;
    case Material::kHat: c = l.hat; break;
    case Material::kBag: c = l.bag; break;
    case Material::kHead: {
      const cv::Vec3d e = (q - m.head_centre);
      const double ex = e[0] / m.head_radii[0], ey = e[1] / m.head_radii[1], ez = e[2] / m.head_radii[2];
      const bool face = ez < -0.25 && ey < 0.45;  // front of the head, below the hairline
      const bool hair = !face && (ey > -0.2 || ez > 0.2 || (l.long_hair && ez > -0.3));
      c = hair ? l.hair : l.skin;
      if (face && ey > 0.02 && ey < 0.2 && std::abs(std::abs(ex) - 0.38) < 0.12) c = cv::Vec3f(40, 35, 35);  // eyes
      if (face && ey < -0.45 && ey > -0.58 && std::abs(ex) < 0.3) c = c * 0.7f;                             // mouth
      break;
    }
    case Material::kTop: {
      c = l.top;
      const double band = 0.06 * l.height / 1.75;
      const bool hs = static_cast<int>(std::floor(q[1] / band)) % 2 != 0;
      const double around = std::atan2(q[0], q[2]);
      const bool vs = static_cast<int>(std::floor(around * 6 / M_PI + 100)) % 2 != 0;
      if ((l.top_pattern == 1 && hs) || (l.top_pattern == 2 && vs) || (l.top_pattern == 3 && (hs != vs))) c = l.top2;
      const double chest = l.height * 0.72;
      if (l.chest_print && q[2] < -0.04 && std::abs(q[0]) < 0.07 * l.height / 1.75 && std::abs(q[1] - chest) < 0.055 * l.height / 1.75)
        c = cv::Vec3f(245, 245, 245) - l.top * 0.6f;
      break;
    }
    case Material::kBottom: {
      c = l.bottom;
      if (l.bottom_pattern == 1 && std::abs(std::abs(q[0]) - l.hips * 0.33) < 0.02 && q[1] < l.height * 0.5) c = l.bottom2;
      break;
    }
  }
  // Lambert light from above the camera plus ambient.
  const cv::Vec3f light(0.25f, 0.55f, -0.80f);
  const float lambert = std::max(0.f, n.dot(light) / static_cast<float>(cv::norm(light)));
  return c * (0.38f + 0.62f * lambert);
}

}  // namespace bodyrec::synth
