#include "bodyrec/rgbd/openni_source.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

#ifdef BODYREC_HAVE_OPENNI2
#include <OpenNI.h>
#endif
#ifdef __SANITIZE_ADDRESS__
#include <sanitizer/lsan_interface.h>
#endif

namespace bodyrec {

#ifdef BODYREC_HAVE_OPENNI2

namespace {

Intrinsics from_fov(int width, int height, double hfov, double vfov) {
  Intrinsics k;
  k.width = width;
  k.height = height;
  k.fx = width / (2.0 * std::tan(hfov / 2.0));
  k.fy = height / (2.0 * std::tan(vfov / 2.0));
  k.cx = (width - 1) / 2.0;
  k.cy = (height - 1) / 2.0;
  return k;
}

std::string last_error() {
  const std::string e = openni::OpenNI::getExtendedError();
  std::string one_line;
  for (char c : e) one_line += (c == '\n' || c == '\r') ? ' ' : c;
  return one_line.empty() ? "no details" : one_line;
}

// OpenNI2's drivers (libPS1080, libPSLink, libOniFile, libDummyDevice, dlopened by initialize()) allocate
// about 110 kB in their static initialisers and never free it; shutdown() unloads them, so LeakSanitizer
// reports 1576 leaks from "<unknown module>" at exit. A 10-line program that only calls initialize() and
// shutdown() reports the same. Under the sanitizers, allocations made inside initialize() are not leak-checked
// (docs/reliability.md); everything bodyrec allocates is.
openni::Status initialise_openni() {
#ifdef __SANITIZE_ADDRESS__
  __lsan::ScopedDisabler third_party_leaks;
#endif
  return openni::OpenNI::initialize();
}

}  // namespace

struct OpenNiSource::Impl {
  openni::Device device;
  openni::VideoStream depth, color;
  bool has_color = false;
  RecordingMeta meta;
  int next = 0;
  ~Impl() {
    depth.stop();
    color.stop();
    depth.destroy();
    color.destroy();
    device.close();
    openni::OpenNI::shutdown();
  }
};

bool openni2_supported() { return true; }

OpenNiSource::OpenNiSource(const std::string& uri) {
  if (initialise_openni() != openni::STATUS_OK)
    throw InputError("OpenNI2: cannot initialise (" + last_error() + ")");
  impl_ = std::make_unique<Impl>();
  openni::Array<openni::DeviceInfo> devices;
  openni::OpenNI::enumerateDevices(&devices);
  if (devices.getSize() == 0 && uri.empty())
    throw InputError("OpenNI2: no RGB-D device found (connect a Kinect v1, Xtion or Orbbec sensor)");
  if (impl_->device.open(uri.empty() ? openni::ANY_DEVICE : uri.c_str()) != openni::STATUS_OK)
    throw InputError("OpenNI2: cannot open device " + (uri.empty() ? std::string("(first)") : uri) + " (" +
                     last_error() + ")");
  if (impl_->depth.create(impl_->device, openni::SENSOR_DEPTH) != openni::STATUS_OK)
    throw InputError("OpenNI2: device has no depth stream (" + last_error() + ")");
  openni::VideoMode mode = impl_->depth.getVideoMode();
  mode.setPixelFormat(openni::PIXEL_FORMAT_DEPTH_1_MM);
  impl_->depth.setVideoMode(mode);
  impl_->has_color = impl_->device.hasSensor(openni::SENSOR_COLOR) &&
                     impl_->color.create(impl_->device, openni::SENSOR_COLOR) == openni::STATUS_OK;
  if (impl_->has_color) {
    openni::VideoMode cm = impl_->color.getVideoMode();
    cm.setPixelFormat(openni::PIXEL_FORMAT_RGB888);
    impl_->color.setVideoMode(cm);
  }
  const bool registered =
      impl_->has_color && impl_->device.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR) &&
      impl_->device.setImageRegistrationMode(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR) == openni::STATUS_OK;
  if (impl_->depth.start() != openni::STATUS_OK) throw InputError("OpenNI2: cannot start depth (" + last_error() + ")");
  if (impl_->has_color && impl_->color.start() != openni::STATUS_OK) impl_->has_color = false;

  RecordingMeta& m = impl_->meta;
  m.sensor = std::string("OpenNI2 ") + impl_->device.getDeviceInfo().getName();
  const openni::VideoMode dm = impl_->depth.getVideoMode();
  m.fps = dm.getFps() > 0 ? dm.getFps() : 30;
  m.depth_unit_m = 0.001;
  m.depth = from_fov(dm.getResolutionX(), dm.getResolutionY(), impl_->depth.getHorizontalFieldOfView(),
                     impl_->depth.getVerticalFieldOfView());
  if (impl_->has_color) {
    const openni::VideoMode cm = impl_->color.getVideoMode();
    m.color = from_fov(cm.getResolutionX(), cm.getResolutionY(), impl_->color.getHorizontalFieldOfView(),
                       impl_->color.getVerticalFieldOfView());
    if (registered && m.color.width == m.depth.width && m.color.height == m.depth.height) m.depth = m.color;
  } else {
    m.color = m.depth;
  }
  m.streams.depth = true;
  m.streams.color = impl_->has_color;
}

OpenNiSource::~OpenNiSource() = default;

const RecordingMeta& OpenNiSource::meta() const { return impl_->meta; }

void OpenNiSource::read(RgbdFrame& frame) {
  openni::VideoStream* depth = &impl_->depth;
  int which = -1;
  if (openni::OpenNI::waitForAnyStream(&depth, 1, &which, 2000) != openni::STATUS_OK)
    throw ProcessingError("OpenNI2: no depth frame within 2 s (" + last_error() + ")");
  openni::VideoFrameRef df;
  if (impl_->depth.readFrame(&df) != openni::STATUS_OK) throw ProcessingError("OpenNI2: cannot read depth (" + last_error() + ")");
  frame = RgbdFrame();
  frame.index = impl_->next++;
  frame.time_s = frame.index / impl_->meta.fps;
  cv::Mat(df.getHeight(), df.getWidth(), CV_16U, const_cast<void*>(df.getData()), static_cast<size_t>(df.getStrideInBytes()))
      .copyTo(frame.depth);
  if (impl_->has_color) {
    openni::VideoFrameRef cf;
    if (impl_->color.readFrame(&cf) != openni::STATUS_OK)
      throw ProcessingError("OpenNI2: cannot read colour (" + last_error() + ")");
    const cv::Mat rgb(cf.getHeight(), cf.getWidth(), CV_8UC3, const_cast<void*>(cf.getData()),
                      static_cast<size_t>(cf.getStrideInBytes()));
    cv::cvtColor(rgb, frame.color, cv::COLOR_RGB2BGR);
  }
}

#else  // no OpenNI2 in this build

struct OpenNiSource::Impl {};

bool openni2_supported() { return false; }

OpenNiSource::OpenNiSource(const std::string&) {
  throw InputError(
      "OpenNI2: this bodyrec was built without OpenNI2 support (install libopenni2-dev and configure with "
      "-DBODYREC_WITH_OPENNI2=ON)");
}

OpenNiSource::~OpenNiSource() = default;

const RecordingMeta& OpenNiSource::meta() const {
  static const RecordingMeta none;
  return none;
}

void OpenNiSource::read(RgbdFrame&) { throw ProcessingError("OpenNI2: not supported in this build"); }

#endif

}  // namespace bodyrec
