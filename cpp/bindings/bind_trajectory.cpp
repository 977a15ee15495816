// The timed trajectory and its contact wrenches.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>

#include "common.hpp"
#include "convert.hpp"
#include "docstrings.hpp"
#include "pathpace/constraints/contact_constraint.hpp"
#include "pathpace/contact_wrenches.hpp"
#include "pathpace/cubic_spline_path.hpp"
#include "pathpace/robot_model.hpp"
#include "pathpace/trajectory.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace pathpace::python {

namespace {

using TrajectoryClass = py::class_<Trajectory, std::shared_ptr<Trajectory>>;

// Trajectory.contact_wrenches: the C++ result, with whether t was a scalar (then no sample axis).
struct WrenchSamples {
  ContactWrenches w;
  bool scalar = false;
  // (samples, 3 L) -> (samples, L, 3), or (L, 3) for a scalar t.
  py::array_t<double> per_link(const Eigen::MatrixXd& a) const {
    const auto S = static_cast<py::ssize_t>(a.rows()), L = static_cast<py::ssize_t>(w.links.size());
    py::array_t<double> out = scalar ? py::array_t<double>({L, py::ssize_t(3)}) : py::array_t<double>({S, L, py::ssize_t(3)});
    double* d = out.mutable_data();
    for (py::ssize_t i = 0; i < (scalar ? 1 : S); ++i)
      for (py::ssize_t c = 0; c < 3 * L; ++c) d[i * 3 * L + c] = a(i, c);
    return out;
  }
};

WrenchSamples wrench_samples(const Trajectory& tr, py::handle t, py::handle distribution) {
  const ForceDistribution dist = parse_distribution(distribution);
  const Eigen::VectorXd tv = to_vector(t, "t");
  WrenchSamples out;
  out.scalar = is_scalar(t);
  py::gil_scoped_release release;  // the force-distribution LPs
  out.w = tr.contact_wrenches(tv, dist);
  return out;
}

// q, qd or qdd at scalar or array t; a scalar gives a 1-D row.
py::object at_times(const Trajectory& tr, py::handle t, int which) { return evaluate_at(tr, t, to_vector(t, "t"), which); }

py::dict samples_dict(const Trajectory::Samples& s) {
  return py::dict("t"_a = s.t, "q"_a = s.q, "qd"_a = s.qd, "qdd"_a = s.qdd);
}

void bind_contact_wrenches(py::module_& m) {
  py::class_<WrenchSamples>(m, "ContactWrenches", doc::ContactWrenches)
      .def_property_readonly("links", [](const WrenchSamples& w) { return w.w.links; }, doc::ContactWrenches_links)
      .def_property_readonly("force", [](const WrenchSamples& w) { return w.per_link(w.w.force); }, doc::ContactWrenches_force)
      .def_property_readonly("moment", [](const WrenchSamples& w) { return w.per_link(w.w.moment); },
                             doc::ContactWrenches_moment)
      .def_property_readonly("center_of_pressure", [](const WrenchSamples& w) { return w.per_link(w.w.center_of_pressure); },
                             doc::ContactWrenches_center_of_pressure)
      .def_property_readonly("normal_force", [](const WrenchSamples& w) -> py::object {
        if (w.scalar) return py::cast(Eigen::VectorXd(w.w.normal_force.row(0).transpose()));
        return py::cast(w.w.normal_force);
      }, doc::ContactWrenches_normal_force)
      .def_property_readonly("margin", [](const WrenchSamples& w) -> py::object {
        return w.scalar ? py::object(py::float_(w.w.margin[0])) : py::cast(w.w.margin);
      }, doc::ContactWrenches_margin)
      .def_property_readonly("feasible", [](const WrenchSamples& w) -> py::object {
        return w.scalar ? py::object(py::bool_(w.w.feasible[0])) : py::cast(w.w.feasible);
      }, doc::ContactWrenches_feasible)
      .def_property_readonly("phase", [](const WrenchSamples& w) -> py::object {
        return w.scalar ? py::object(py::int_(w.w.phase[0])) : py::cast(w.w.phase);
      }, doc::ContactWrenches_phase);
}

void bind_trajectory_timing(TrajectoryClass& cls) {
  cls.def(py::init([](py::handle path, py::handle s, py::handle sdot, py::handle sddot_points) {
       if (sddot_points.is_none())
         return std::make_shared<Trajectory>(to_object<Path>(path, "path", "Path"), to_vector(s, "s"), to_vector(sdot, "sdot"));
       return std::make_shared<Trajectory>(to_object<Path>(path, "path", "Path"), to_vector(s, "s"), to_vector(sdot, "sdot"),
                                           to_vector(sddot_points, "sddot_points"));
     }),
     "path"_a, "s"_a, "sdot"_a, "sddot_points"_a = py::none())
      .def_property_readonly("sddot_points", [](const Trajectory& t) -> py::object {
        return t.sddot_points().size() ? py::cast(t.sddot_points()) : py::object(py::none());
      }, doc::Trajectory_sddot_points)
      .def("qddd", [](const Trajectory& tr, py::handle t) -> py::object {
        const Eigen::MatrixXd j = tr.qddd(to_vector(t, "t"));
        if (is_scalar(t)) return py::cast(Eigen::VectorXd(j.row(0).transpose()));
        return py::cast(j);
      }, "t"_a, doc::Trajectory_qddd)
      .def_property_readonly("duration", &Trajectory::duration, doc::Trajectory_duration)
      .def_property_readonly("times", &Trajectory::times, doc::Trajectory_times)
      .def_property_readonly("grid", &Trajectory::grid, doc::Trajectory_grid)
      .def_property_readonly("sdot_grid", &Trajectory::sdot_grid, doc::Trajectory_sdot_grid)
      .def_property_readonly("path", [](const Trajectory& t) { return std::const_pointer_cast<Path>(t.path()); },
                             doc::Trajectory_path)
      .def_property_readonly("robot", [](const Trajectory& tr) { return std::const_pointer_cast<RobotModel>(tr.robot()); },
                             doc::Trajectory_robot)
      .def("s", [](const Trajectory& tr, py::handle t) -> py::tuple {
        Eigen::VectorXd s, sd, sdd;
        tr.evaluate_s(to_vector(t, "t"), s, sd, sdd);
        if (is_scalar(t)) return py::make_tuple(s[0], sd[0], sdd[0]);
        return py::make_tuple(s, sd, sdd);
      }, "t"_a, doc::Trajectory_s)
      .def("q", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 0); }, "t"_a, doc::Trajectory_q)
      .def("qd", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 1); }, "t"_a, doc::Trajectory_qd)
      .def("qdd", [](const Trajectory& tr, py::handle t) { return at_times(tr, t, 2); }, "t"_a, doc::Trajectory_qdd)
      .def("evaluate", [](const Trajectory& tr, py::handle t) {
        return py::make_tuple(at_times(tr, t, 0), at_times(tr, t, 1), at_times(tr, t, 2));
      }, "t"_a, doc::Trajectory_evaluate)
      .def("__call__", [](const Trajectory& tr, py::handle t, py::handle order_arg) {
        const int order = to_int32(order_arg, "order");
        if (order < 0 || order > 2) throw InvalidInput("order = " + std::to_string(order) + " must be 0, 1 or 2");
        return at_times(tr, t, order);
      }, "t"_a, "order"_a = 0, doc::Trajectory_call_)
      .def("torques", [](const Trajectory& tr, py::handle t, py::handle robot_arg) {
        const auto robot = robot_arg.is_none() ? nullptr : to_object<RobotModel>(robot_arg, "robot", "RobotModel");
        const RobotModel* r = robot ? robot.get() : tr.robot().get();
        if (!r) throw InvalidInput("robot: this trajectory was not shaped by torque limits; pass robot=");
        const Eigen::VectorXd tv = to_vector(t, "t");
        Eigen::MatrixXd tau;
        {
          py::gil_scoped_release release;
          tau = tr.torques(tv, *r);
        }
        return rows_at(t, tau);
      }, "t"_a, "robot"_a = py::none(), doc::Trajectory_torques);
}

void bind_trajectory_contacts(TrajectoryClass& cls) {
  cls.def("contact_forces", [](const Trajectory& tr, py::handle t, py::handle distribution) {
       const ForceDistribution dist = parse_distribution(distribution);
       const Eigen::VectorXd tv = to_vector(t, "t");
       std::vector<ContactForces> out;
       Eigen::VectorXi phase;  // with the forces, inside the release: the phase of each t is evaluated once
       {
         py::gil_scoped_release release;
         out = tr.contact_forces(tv, &phase, dist);
       }
       if (tr.contact_phases().empty())
         return to_force_samples(out, static_cast<int>(tr.contacts()->contacts().size()), tr.contacts()->robot()->nq(),
                                 is_scalar(t));
       size_t m = 0;
       for (const auto& c : tr.contact_phases()) m = std::max(m, c->contacts().size());
       ForceSamples f = to_force_samples(out, static_cast<int>(m), tr.contact_phases()[0]->robot()->nq(), is_scalar(t));
       f.phase = std::move(phase);
       return f;
     }, "t"_a, "distribution"_a = "centre", doc::Trajectory_contact_forces)
      .def("contact_wrenches", &wrench_samples, "t"_a, "distribution"_a = "centre", doc::Trajectory_contact_wrenches)
      .def("centers_of_pressure", [](const Trajectory& tr, py::handle t, py::handle distribution) {
        const WrenchSamples w = wrench_samples(tr, t, distribution);
        return w.per_link(w.w.center_of_pressure);
      }, "t"_a, "distribution"_a = "centre", doc::Trajectory_centers_of_pressure)
      .def("contact_phase", [](const Trajectory& tr, py::handle t) -> py::object {
        const Eigen::VectorXi out = tr.contact_phase(to_vector(t, "t"));
        return is_scalar(t) ? py::object(py::int_(out[0])) : py::cast(out);
      }, "t"_a, doc::Trajectory_contact_phase)
      .def_property_readonly("contact_phases", [](const Trajectory& tr) {
        std::vector<std::shared_ptr<ContactConstraint>> out;
        for (const auto& c : tr.contact_phases()) out.push_back(std::const_pointer_cast<ContactConstraint>(c));
        return out;
      }, doc::Trajectory_contact_phases)
      .def_property_readonly("contacts", [](const Trajectory& tr) { return std::const_pointer_cast<ContactConstraint>(tr.contacts()); },
                             doc::Trajectory_contacts);
}

void bind_trajectory_sampling(TrajectoryClass& cls) {
  cls.def("sample", [](const Trajectory& tr, py::handle dt_arg, py::handle max_memory_arg) {
       const double dt = to_double(dt_arg, "dt");
       const double max_memory = to_double(max_memory_arg, "max_memory");
       Trajectory::Samples out;
       {
         py::gil_scoped_release release;
         out = tr.sample(dt, max_memory);
       }
       return samples_dict(out);
     }, "dt"_a, "max_memory"_a = 1e9, doc::Trajectory_sample)
      .def("resample", [](const Trajectory& tr, py::handle dt, py::handle spline_arg) {
        const bool spline = to_bool(spline_arg, "spline");
        const bool at_grid = dt.is_none();
        const double step = at_grid ? 0.0 : to_double(dt, "dt");
        Trajectory::Samples out;
        {
          py::gil_scoped_release release;
          out = at_grid ? tr.sample_at(tr.times(), spline) : tr.sample(step, 1e9, spline);
        }
        return samples_dict(out);
      }, "dt"_a = py::none(), "spline"_a = false, doc::Trajectory_resample)
      .def("sample_times", [](const Trajectory& tr, py::handle dt) { return tr.sample_times(to_double(dt, "dt")); }, "dt"_a,
           doc::Trajectory_sample_times)
      .def("time_spline", [](const Trajectory& tr) {
        py::gil_scoped_release release;
        return std::make_shared<CubicSplinePath>(tr.time_spline());
      }, doc::Trajectory_time_spline)
      // The message layout (ROS field names, plain floats) is Python's: pathpace.export.
      .def("to_joint_trajectory", [](py::object self, py::handle dt, py::handle joint_names, py::handle robot, py::handle spline) {
        return py::module_::import("pathpace.export").attr("to_joint_trajectory")(self, dt, joint_names, robot, spline);
      }, "dt"_a = py::none(), "joint_names"_a = py::none(), "robot"_a = py::none(), "spline"_a = false,
         doc::Trajectory_to_joint_trajectory);
}

}  // namespace

void bind_trajectory(py::module_& m) {
  bind_contact_wrenches(m);
  TrajectoryClass cls(m, "Trajectory", doc::Trajectory);
  bind_trajectory_timing(cls);
  bind_trajectory_contacts(cls);
  bind_trajectory_sampling(cls);
  cls.def(py::pickle([](const Trajectory& tr) {
                       return py::make_tuple(std::const_pointer_cast<Path>(tr.path()), tr.grid(), tr.sdot_grid(),
                                             std::const_pointer_cast<RobotModel>(tr.robot()),
                                             std::const_pointer_cast<ContactConstraint>(tr.contacts()),
                                             phases_list(tr.contact_phases()), tr.sddot_points());
                     },
                     [](const py::tuple& t) {
                       if (t.size() != 6) check_state(t, 7, "Trajectory");  // 6: before jerk-limited timings
                       const bool jerk = t.size() == 7 && to_vector(t[6], "sddot_points").size() > 0;
                       auto tr = jerk ? std::make_shared<Trajectory>(t[0].cast<std::shared_ptr<Path>>(), to_vector(t[1], "s"),
                                                                     to_vector(t[2], "sdot"), to_vector(t[6], "sddot_points"))
                                      : std::make_shared<Trajectory>(t[0].cast<std::shared_ptr<Path>>(), to_vector(t[1], "s"),
                                                                     to_vector(t[2], "sdot"));
                       tr->set_robot(optional_ptr<RobotModel>(t[3]));
                       tr->set_contacts(optional_ptr<ContactConstraint>(t[4]));
                       tr->set_contact_phases(phases_vector(t[5]));
                       return tr;
                     }))
      .def("__repr__", [](const Trajectory& tr) {
        std::string s = "<Trajectory duration=" + short_number(tr.duration()) + " s dof=" +
                        std::to_string(tr.path()->dof()) + " grid_points=" + std::to_string(tr.grid().size());
        if (tr.robot()) s += " robot='" + tr.robot()->name() + "'";
        if (!tr.contact_phases().empty()) s += " contact_phases=" + std::to_string(tr.contact_phases().size());
        else if (tr.contacts()) s += " contacts=" + std::to_string(tr.contacts()->contacts().size());
        return s + ">";
      });
}

}  // namespace pathpace::python
