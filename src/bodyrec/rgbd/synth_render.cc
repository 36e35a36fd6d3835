#include "bodyrec/rgbd/synth_render.h"

#include <algorithm>
#include <cmath>

namespace bodyrec::synth {
namespace {

// Nearest hit t (= Z) of ray o + t d with the primitive, and the unit normal there; t <= 0 when missed.
inline float hit(const Primitive& p, const cv::Vec3f& d, const cv::Vec3f& a, const cv::Vec3f& b, cv::Vec3f& normal) {
  if (p.capsule) {
    const cv::Vec3f ba = b - a, oa = -a;
    const float baba = ba.dot(ba), bard = ba.dot(d), baoa = ba.dot(oa), rdoa = d.dot(oa), oaoa = oa.dot(oa),
                dd = d.dot(d), rr = p.r * p.r;
    const float A = baba * dd - bard * bard, B = baba * rdoa - baoa * bard, C = baba * oaoa - baoa * baoa - rr * baba;
    float h = B * B - A * C;
    if (h < 0) return -1;
    if (A > 1e-12f) {
      const float t = (-B - std::sqrt(h)) / A;
      const float y = baoa + t * bard;
      if (y > 0 && y < baba) {
        const cv::Vec3f pt = d * t, q = a + ba * (y / baba);
        normal = (pt - q) * (1.f / p.r);
        return t;
      }
    }
    // End caps: spheres at a or b.
    float best = -1;
    for (const cv::Vec3f* c : {&a, &b}) {
      const cv::Vec3f oc = -*c;
      const float bb = d.dot(oc), cc = oc.dot(oc) - rr;
      const float hh = bb * bb - dd * cc;
      if (hh < 0) continue;
      const float t = (-bb - std::sqrt(hh)) / dd;
      if (t > 0 && (best < 0 || t < best)) {
        best = t;
        normal = (d * t - *c) * (1.f / p.r);
      }
    }
    return best;
  }
  const cv::Vec3f o = p.m * (-a), dm = p.m * d;
  const float A = dm.dot(dm), B = o.dot(dm), C = o.dot(o) - 1;
  const float h = B * B - A * C;
  if (h < 0) return -1;
  const float t = (-B - std::sqrt(h)) / A;
  const cv::Vec3f s = o + dm * t;  // point on the unit sphere; normal = M^T s
  normal = p.m.t() * s;
  normal *= 1.f / static_cast<float>(cv::norm(normal));
  return t;
}

// Pixels a primitive may cover: the projected end points widened by the radius at the nearest depth,
// clipped to the image grown by `pad`. False when the primitive is behind or too close to the camera.
bool screen_box(const Primitive& p, const Intrinsics& k, const cv::Vec3f& offset, int pad, int& u0, int& u1, int& v0,
                int& v1) {
  const float fx = static_cast<float>(k.fx), fy = static_cast<float>(k.fy), cx = static_cast<float>(k.cx),
              cy = static_cast<float>(k.cy);
  const cv::Vec3f a = p.a + offset, b = p.b + offset;
  const float zmin = std::min(a[2], b[2]) - p.r;
  if (zmin < 0.2f) return false;
  const float ua = cx + fx * a[0] / a[2], va = cy - fy * a[1] / a[2], ub = cx + fx * b[0] / b[2], vb = cy - fy * b[1] / b[2];
  const float ru = fx * p.r / zmin + 1, rv = fy * p.r / zmin + 1;
  u0 = std::max(-pad, static_cast<int>(std::floor(std::min(ua, ub) - ru)));
  u1 = std::min(k.width - 1 + pad, static_cast<int>(std::ceil(std::max(ua, ub) + ru)));
  v0 = std::max(-pad, static_cast<int>(std::floor(std::min(va, vb) - rv)));
  v1 = std::min(k.height - 1 + pad, static_cast<int>(std::ceil(std::max(va, vb) + rv)));
  return true;
}

}  // namespace

bool may_cover_image(const PersonModel& model, const Intrinsics& k) {
  int u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  for (const Primitive& p : model.primitives)
    if (screen_box(p, k, cv::Vec3f(0, 0, 0), 0, u0, u1, v0, v1) && u0 <= u1 && v0 <= v1) return true;
  return false;
}

void draw_person(const Look& look, const PersonModel& model, int label, Target& tg, cv::Mat* coverage) {
  const Intrinsics& k = tg.k;
  const int w = k.width, h = k.height, pad = coverage ? tg.pad : 0;
  const float fx = static_cast<float>(k.fx), fy = static_cast<float>(k.fy), cx = static_cast<float>(k.cx),
              cy = static_cast<float>(k.cy);
  for (const Primitive& p : model.primitives) {
    const cv::Vec3f a = p.a + tg.offset, b = p.b + tg.offset;
    int u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    if (!screen_box(p, k, tg.offset, pad, u0, u1, v0, v1)) continue;  // behind or too close to the camera
    for (int v = v0; v <= v1; ++v) {
      const bool row_in = v >= 0 && v < h;
      if (!row_in && !coverage) continue;
      float* zrow = row_in ? tg.z.ptr<float>(v) : nullptr;
      const float dy = (cy - static_cast<float>(v)) / fy;
      for (int u = u0; u <= u1; ++u) {
        const bool in = row_in && u >= 0 && u < w;
        if (!in && !coverage) continue;
        const cv::Vec3f d((static_cast<float>(u) - cx) / fx, dy, 1.f);
        cv::Vec3f n;
        const float t = hit(p, d, a, b, n);
        if (t <= 0) continue;
        if (coverage) coverage->at<uint8_t>(v + pad, u + pad) = 1;
        if (!in || t >= zrow[u]) continue;
        zrow[u] = t;
        if (!tg.label.empty()) tg.label.at<uint8_t>(v, u) = static_cast<uint8_t>(label);
        if (!tg.color.empty()) {
          const cv::Vec3f c = shade(look, model, p.material, d * t - tg.offset, n);
          tg.color.at<cv::Vec3b>(v, u) = cv::Vec3b(cv::saturate_cast<uint8_t>(c[0]), cv::saturate_cast<uint8_t>(c[1]),
                                                   cv::saturate_cast<uint8_t>(c[2]));
        }
      }
    }
  }
}

void draw_room(Target& tg, double camera_height) {
  const Intrinsics& k = tg.k;
  const double floor_y = -camera_height, ceiling_y = 2.6 - camera_height, back_z = 5.2, side_x = 3.4;
  tg.z.create(k.height, k.width, CV_32F);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const cv::Vec3d d((u - k.cx) / k.fx, (k.cy - v) / k.fy, 1.0);
      const cv::Vec3d o = -cv::Vec3d(tg.offset);
      // Nearest of the five planes the ray meets going outwards.
      double t = (back_z - o[2]) / d[2];
      int plane = 0;  // 0 back wall, 1 floor, 2 ceiling, 3 left wall, 4 right wall
      const auto consider = [&](double tt, int id) {
        if (tt > 0 && tt < t) t = tt, plane = id;
      };
      if (d[1] < 0) consider((floor_y - o[1]) / d[1], 1);
      if (d[1] > 0) consider((ceiling_y - o[1]) / d[1], 2);
      if (d[0] < 0) consider((-side_x - o[0]) / d[0], 3);
      if (d[0] > 0) consider((side_x - o[0]) / d[0], 4);
      const cv::Vec3d p = o + d * t;
      tg.z.at<float>(v, u) = static_cast<float>(p[2] + tg.offset[2]);
      if (tg.color.empty()) continue;
      cv::Vec3d c;
      if (plane == 1) {  // floor tiles
        const bool tile = (static_cast<int>(std::floor(p[0] / 0.5)) + static_cast<int>(std::floor(p[2] / 0.5))) % 2 != 0;
        c = tile ? cv::Vec3d(120, 135, 150) : cv::Vec3d(105, 118, 132);
      } else if (plane == 2) {
        c = {225, 225, 225};
      } else if (plane == 0) {  // wall with a door and a picture
        c = {185, 205, 215};
        if (p[0] > 1.0 && p[0] < 1.9 && p[1] < floor_y + 2.05) c = {60, 90, 130};
        if (p[0] > -1.6 && p[0] < -0.6 && p[1] > floor_y + 1.3 && p[1] < floor_y + 1.9) c = {150, 110, 60};
      } else {
        c = plane == 3 ? cv::Vec3d(170, 190, 200) : cv::Vec3d(160, 180, 195);
      }
      const double fade = 1.0 / (1.0 + 0.05 * t);  // a little darker far away
      tg.color.at<cv::Vec3b>(v, u) = cv::Vec3b(cv::saturate_cast<uint8_t>(c[0] * fade), cv::saturate_cast<uint8_t>(c[1] * fade),
                                               cv::saturate_cast<uint8_t>(c[2] * fade));
    }
}

}  // namespace bodyrec::synth
