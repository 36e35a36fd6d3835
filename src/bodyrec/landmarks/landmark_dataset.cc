#include "bodyrec/landmarks/landmark_dataset.h"

#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/imglab_xml.h"

namespace bodyrec {

int LandmarkDataset::people() const {
  int n = 0;
  for (const auto& image : images) n += static_cast<int>(image.people.size());
  return n;
}

LandmarkDataset load_landmark_dataset(const std::string& xml_path, bool load_images) {
  const ImglabDataset xml = read_imglab(xml_path);
  LandmarkDataset dataset;
  for (const auto& image : xml.images) {
    AnnotatedImage out;
    out.path = resolve_image_path(xml_path, image.file);
    const std::string where = xml_path + ": image " + image.file;
    if (load_images) {
      out.image = cv::imread(out.path, cv::IMREAD_COLOR);
      if (out.image.empty()) throw InputError(where + ": cannot read image " + out.path);
    }
    int index = 0;
    for (const auto& box : image.boxes) {
      const std::string box_where = where + ": box " + std::to_string(index++);
      AnnotatedPerson person{box.box, ordered_parts(box, box_where), box.ignore};
      if (!person.landmarks.empty()) {
        const int n = static_cast<int>(person.landmarks.size());
        if (dataset.landmarks == 0) dataset.landmarks = n;
        if (n != dataset.landmarks)
          throw InputError(box_where + ": has " + std::to_string(n) + " landmarks, earlier boxes have " +
                           std::to_string(dataset.landmarks));
      }
      out.people.push_back(std::move(person));
    }
    dataset.images.push_back(std::move(out));
  }
  return dataset;
}

ImglabBox imglab_landmark_box(const Box& box, const std::vector<cv::Point2d>& points) {
  ImglabBox b;
  b.box = box;
  for (size_t i = 0; i < points.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%02zu", i);
    b.parts.push_back({name, points[i]});
  }
  return b;
}

void write_landmark_dataset(const LandmarkDataset& data, const std::string& xml_path, const std::string& name) {
  ImglabDataset out;
  out.name = name;
  for (const auto& image : data.images) {
    ImglabImage entry;
    entry.file = std::filesystem::absolute(image.path).string();
    for (const auto& person : image.people) {
      ImglabBox box = imglab_landmark_box(person.box, person.landmarks);
      box.ignore = person.ignore;
      entry.boxes.push_back(std::move(box));
    }
    out.images.push_back(std::move(entry));
  }
  write_imglab(out, xml_path);
}

}  // namespace bodyrec
