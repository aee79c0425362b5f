// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
#include "obstacle_tracker/ros/conversions.h"

#include <cmath>
#include <limits>
#include <sstream>

#include <boost/any.hpp>
#include <dynamic_reconfigure/config_tools.h>
#include <xmlrpcpp/XmlRpcValue.h>

namespace obstacle_tracker {
namespace bridge {

namespace {

void setChecked(core::Params& params, const std::string& name, double value, const char* source,
                std::vector<std::string>* messages) {
  std::string message;
  core::setParam(params, name, value, &message);
  if (!message.empty() && messages) messages->push_back(std::string(source) + ": " + message);
}

const ObstacleTrackerConfig::AbstractParamDescriptionConstPtr* findDescription(const std::string& name) {
  for (const auto& desc : ObstacleTrackerConfig::__getParamDescriptions__()) {
    if (desc->name == name) return &desc;
  }
  return nullptr;
}

}  // namespace

core::Params paramsFromRos(const ros::NodeHandle& nh, const core::Params& base,
                           std::vector<std::string>* messages) {
  core::Params params = base;
  for (const core::ParamInfo& info : core::paramTable()) {
    XmlRpc::XmlRpcValue value;
    if (!nh.getParam(info.name, value)) continue;
    double number;
    switch (value.getType()) {
      case XmlRpc::XmlRpcValue::TypeBoolean: number = static_cast<bool>(value) ? 1.0 : 0.0; break;
      case XmlRpc::XmlRpcValue::TypeInt: number = static_cast<int>(value); break;
      case XmlRpc::XmlRpcValue::TypeDouble: number = static_cast<double>(value); break;
      default: {
        std::ostringstream msg;
        msg << "ROS parameter " << nh.resolveName(info.name) << ": expected a number, got '"
            << value.toXml() << "'; keeping " << core::getParam(params, info.name);
        if (messages) messages->push_back(msg.str());
        continue;
      }
    }
    setChecked(params, info.name, number, ("ROS parameter " + nh.resolveName(info.name)).c_str(), messages);
  }
  return params;
}

core::Params paramsFromConfig(const ObstacleTrackerConfig& config, const core::Params& base,
                              std::vector<std::string>* messages) {
  core::Params params = base;
  for (const auto& desc : ObstacleTrackerConfig::__getParamDescriptions__()) {
    if (core::findParam(desc->name) == nullptr) continue;
    boost::any value;
    desc->getValue(config, value);
    double number;
    if (desc->type == "bool") {
      number = boost::any_cast<bool>(value) ? 1.0 : 0.0;
    } else if (desc->type == "int") {
      number = boost::any_cast<int>(value);
    } else if (desc->type == "double") {
      number = boost::any_cast<double>(value);
    } else {
      continue;
    }
    setChecked(params, desc->name, number, "dynamic_reconfigure", messages);
  }
  return params;
}

ObstacleTrackerConfig configFromParams(const core::Params& params, const ObstacleTrackerConfig& base) {
  dynamic_reconfigure::Config msg;
  for (const core::ParamInfo& info : core::paramTable()) {
    const auto* desc = findDescription(info.name);
    if (desc == nullptr) continue;
    const double value = core::getParam(params, info.name);
    const std::string& type = (*desc)->type;
    if (type == "bool") {
      dynamic_reconfigure::ConfigTools::appendParameter(msg, info.name, value != 0.0);
    } else if (type == "int") {
      dynamic_reconfigure::ConfigTools::appendParameter(msg, info.name, static_cast<int>(std::lround(value)));
    } else if (type == "double") {
      dynamic_reconfigure::ConfigTools::appendParameter(msg, info.name, value);
    }
  }
  ObstacleTrackerConfig config = base;
  config.__fromMessage__(msg);
  return config;
}

std::vector<std::string> paramsMissingFromConfig() {
  std::vector<std::string> missing;
  for (const core::ParamInfo& info : core::paramTable()) {
    if (findDescription(info.name) == nullptr) missing.emplace_back(info.name);
  }
  return missing;
}

std::uint8_t toMessageState(core::TrackState state) {
  switch (state) {
    case core::TrackState::kTracking: return obstacle_tracker::Obstacle::STATE_TRACKING;
    case core::TrackState::kRedetecting: return obstacle_tracker::Obstacle::STATE_REDETECTING;
    case core::TrackState::kLost: return obstacle_tracker::Obstacle::STATE_LOST;
    default: return obstacle_tracker::Obstacle::STATE_SEARCHING;
  }
}

void toMessage(const core::Obstacle& o, obstacle_tracker::Obstacle& msg) {
  msg.id = o.id < 0 ? 0u : static_cast<std::uint32_t>(o.id);
  msg.x = o.box.x;
  msg.y = o.box.y;
  msg.width = o.box.width;
  msg.height = o.box.height;
  msg.confidence = o.confidence;
  msg.peak = o.peak;
  msg.psr = o.psr;
  msg.state = toMessageState(o.state);
  msg.confirmed = o.confirmed;
  msg.has_bearing = false;
  msg.bearing.x = msg.bearing.y = msg.bearing.z = 0.0;
  msg.angular_width = 0.0f;
  msg.angular_height = 0.0f;
  msg.bearing_rate = 0.0f;          // the nodelet fills these from the bearings (collision_course.h)
  msg.collision_course = false;
  msg.expansion_rate = static_cast<float>(o.expansion_rate);
  msg.expansion_rate_sigma = static_cast<float>(o.expansion_rate_sigma);
  msg.time_to_contact = std::isnan(o.time_to_contact)
                            ? std::numeric_limits<float>::infinity()
                            : static_cast<float>(o.time_to_contact);
  msg.time_to_contact_sigma = std::isnan(o.time_to_contact_sigma)
                                  ? std::numeric_limits<float>::infinity()
                                  : static_cast<float>(o.time_to_contact_sigma);
}

}  // namespace bridge
}  // namespace obstacle_tracker
