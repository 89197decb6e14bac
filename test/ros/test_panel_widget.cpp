// The control panel's widget against a running node (panel.test), under QT_QPA_PLATFORM=offscreen: what is typed
// and clicked reaches the node (TopState, ~list); the fields follow the top unless typed in; the widget fits the
// dock of rviz/top_sim.rviz with every field wide enough to read.
#include <gtest/gtest.h>

#include <QApplication>
#include <QComboBox>
#include <QFont>
#include <QFontMetrics>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QtTest/QTest>
#include <functional>
#include <iostream>

#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include "control_panel.hpp"
#include "top_sim/ListTops.h"
#include "top_sim/TopState.h"

namespace {

top_sim::TopState g_state;
bool g_have_state = false;

void on_state(const top_sim::TopState::ConstPtr& m) {
  g_state = *m;
  g_have_state = true;
}

// Spins ROS and Qt until `done` holds or `seconds` pass.
bool wait_for(const std::function<bool()>& done, double seconds = 10.0) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < end) {
    ros::spinOnce();
    QApplication::processEvents();
    if (done()) return true;
    ros::WallDuration(0.01).sleep();
  }
  return false;
}

void click(top_sim_rviz::ControlWidget& w, const char* text) {
  for (QPushButton* b : w.findChildren<QPushButton*>())
    if (b->text() == text) return b->click();
  ADD_FAILURE() << "no button " << text;
}

// As a user types: the old text selected and replaced key by key (QLineEdit::textEdited, unlike setText).
void type(QLineEdit* field, const char* text) {
  field->selectAll();
  if (*text == '\0') QTest::keyClick(field, Qt::Key_Backspace);
  QTest::keyClicks(field, text);
}

std::string text(const QLineEdit* field) { return field->text().toStdString(); }

bool starts_with(const std::string& text, const std::string& head) { return text.rfind(head, 0) == 0; }

std::vector<std::string> tops() {
  top_sim::ListTops srv;
  return ros::service::call("/top_sim/list", srv) ? srv.response.names : std::vector<std::string>{};
}

}  // namespace

// The left dock of rviz/top_sim.rviz in its 1280 x 800 window (scripts/rviz_layout.py, no Time panel): 342 x 709
// px, of which the panel's title bar, the dock's tab bar, the node field and the margins leave the widget about
// 330 x 625 px (docs/img/rviz_panel.png: y = 116 to 741). Measured with rviz's font under X (Qt's default there,
// Sans Serif 9 pt; main() sets it for the offscreen platform).
constexpr int kDockWidth = 330, kDockHeight = 620;

// The longest answer the panel gives to a command: two lines at the dock's width.
constexpr const char* kLongAnswer =
    "Sent to top 'top': inclination 0.2 rad, spin 150 rad/s and friction law coulomb with mu 0.35.";

// The answer wholly in view at the widget's bottom, below the groups of fields.
void expect_answer_in_view(const top_sim_rviz::ControlWidget& w) {
  const QLabel* answer = w.answer_label();
  EXPECT_TRUE(answer->isVisible());
  EXPECT_GE(answer->geometry().top(), w.groups_area()->geometry().bottom()) << "the answer is below the fields";
  EXPECT_LE(answer->geometry().bottom(), w.height() - 1) << "the answer is cut off at the dock's bottom";
  EXPECT_GE(answer->height(), answer->heightForWidth(answer->width())) << "the answer's lines are clipped";
}

TEST(PanelWidget, FitsTheDockWithEveryFieldReadableAndTheAnswerInView) {
  top_sim_rviz::ControlWidget w;
  w.resize(kDockWidth, kDockHeight);
  w.show_message(kLongAnswer);
  w.show();
  QApplication::processEvents();
  EXPECT_LE(w.minimumSizeHint().width(), kDockWidth) << "would scroll sideways";
  // At the dock's width (wrapped texts are taller there than at the widget's preferred width).
  const QWidget* groups = w.groups_area()->widget();
  const int width = w.groups_area()->viewport()->width();
  const int needed = groups->hasHeightForWidth() ? groups->heightForWidth(width) : groups->sizeHint().height();
  const int shown = w.groups_area()->viewport()->height();
  EXPECT_LE(needed, shown) << "the fields would need scrolling";
  EXPECT_EQ(w.groups_area()->verticalScrollBar()->maximum(), 0) << "the fields would need scrolling";
  expect_answer_in_view(w);
  const int digits = QFontMetrics(w.font()).horizontalAdvance("-1234.56");
  std::cout << "panel: fields " << needed << " px high of " << shown << " px at " << width << " px, answer "
            << w.answer_label()->height() << " px, minimum width " << w.minimumSizeHint().width()
            << " px; '-1234.56' is " << digits << " px wide\n";
  for (QLineEdit* field : w.findChildren<QLineEdit*>()) {
    if (!field->isVisible()) continue;
    EXPECT_GE(field->width(), digits) << field->placeholderText().toStdString() << ": too narrow to read";
  }
  w.resize(kDockWidth, kDockHeight / 2);  // a smaller window: the fields scroll, the answer stays in view
  QApplication::processEvents();
  EXPECT_GT(w.groups_area()->verticalScrollBar()->maximum(), 0);
  expect_answer_in_view(w);
}

TEST(PanelWidget, ButtonsReachTheNodeAndFieldsFollowTheTop) {
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe("/top_sim/top_state", 10, on_state);
  ros::Publisher inclination = nh.advertise<std_msgs::Float64>("/top_sim/inclination", 1, true);
  ASSERT_TRUE(ros::service::waitForService("/top_sim/reset", ros::Duration(30.0)));
  top_sim_rviz::ControlWidget w;
  ASSERT_TRUE(wait_for([] { return g_have_state; }));
  EXPECT_TRUE(wait_for([&] { return text(w.inclination_field()) == "0.1"; })) << text(w.inclination_field());
  EXPECT_TRUE(wait_for([&] { return text(w.real_time_factor_field()) == "1"; })) << text(w.real_time_factor_field());

  std_msgs::Float64 alpha;  // an inclination sent by topic shows in the field
  alpha.data = 0.15;
  inclination.publish(alpha);
  EXPECT_TRUE(wait_for([&] { return text(w.inclination_field()) == "0.15"; })) << text(w.inclination_field());

  type(w.inclination_field(), "0.2");
  type(w.spin_field(), "150");
  alpha.data = 0.12;  // typed and not applied: the user's text stays
  inclination.publish(alpha);
  EXPECT_TRUE(wait_for([] { return g_state.alpha == 0.12; }));
  EXPECT_EQ(text(w.inclination_field()), "0.2");
  click(w, "Apply to the picked top");
  EXPECT_TRUE(wait_for([] { return g_state.alpha == 0.2 && std::abs(g_state.spin - 150.0) < 2.0; }))
      << "alpha " << g_state.alpha << ", spin " << g_state.spin << "; panel: " << w.message();
  EXPECT_EQ(w.message(), "Sent to top 'top': inclination 0.2 rad and spin 150 rad/s.");

  type(w.inclination_field(), "abc");  // refused in the panel: nothing is sent
  click(w, "Apply to the picked top");
  EXPECT_EQ(w.message(), "Nothing was sent: inclination = 'abc': must be a number.");
  type(w.inclination_field(), "");  // cleared: the field follows the top again, nothing of it is sent
  EXPECT_TRUE(wait_for([&] { return text(w.inclination_field()) == "0.2"; })) << text(w.inclination_field());
  EXPECT_EQ(w.law_field()->itemText(0).toStdString(), "in force: paper");  // the default scene's law (pmma)
  w.law_field()->setCurrentText("coulomb");
  w.parameter_field("mu")->setText("0.35");
  click(w, "Apply to the picked top");
  // Slipping, mu is the law's 0.35; once the contact sticks (Coulomb's mu(0) > 0), the mobilised |F_t| / N within it.
  EXPECT_TRUE(wait_for([] {
    const bool law = g_state.contact_mode == top_sim::TopState::ROLLING ? g_state.mu <= 0.35 + 1e-12
                                                                         : std::abs(g_state.mu - 0.35) < 1e-12;
    return law && g_state.alpha == 0.2 && g_state.friction_law == "coulomb";
  })) << "mu " << g_state.mu << ", mode " << int(g_state.contact_mode) << ", law " << g_state.friction_law
      << "; panel: " << w.message();
  EXPECT_EQ(w.message(), "Sent to top 'top': friction law coulomb with mu 0.35.");
  EXPECT_TRUE(wait_for([&] { return w.law_field()->itemText(0) == "in force: coulomb"; }))  // from TopState
      << w.law_field()->itemText(0).toStdString();

  w.law_field()->setCurrentIndex(0);  // keep the law in force: only the patch is sent
  const double a = 2e-4;
  for (const double radius : {a, 0.0}) {  // a patch, then the point contact again
    w.contact_field("patch_radius")->setText(QString::number(radius));
    click(w, "Apply to the picked top");
    EXPECT_TRUE(wait_for([radius] { return g_state.patch_radius == radius; }))
        << "patch_radius " << g_state.patch_radius << "; panel: " << w.message();
  }
  w.contact_field("patch_radius")->clear();

  click(w, "Pause");
  EXPECT_TRUE(wait_for([] { return g_state.paused; })) << w.message();
  EXPECT_EQ(w.message(), "Paused.");
  click(w, "Resume");
  EXPECT_TRUE(wait_for([] { return !g_state.paused; })) << w.message();
  click(w, "Reset");
  EXPECT_TRUE(wait_for([] { return std::abs(g_state.alpha - 0.1) < 1e-12; })) << "back to the scene's 0.1: " << w.message();
  EXPECT_TRUE(starts_with(w.message(), "Reset top 'top' to its start at t = ")) << w.message();
  EXPECT_TRUE(wait_for([&] { return text(w.inclination_field()) == "0.1"; })) << text(w.inclination_field());

  type(w.spawn_name_field(), "b");
  type(w.spawn_file_field(), "tippe_top");  // a shipped scene by name, as top_sim_run and scene:= take it
  click(w, "Spawn");
  EXPECT_TRUE(wait_for([] { return tops().size() == 2; })) << w.message();
  EXPECT_EQ(w.message(), "Spawned top 'b' (2 tops now).");
  ASSERT_TRUE(wait_for([&] { return w.top_field()->findText("b") >= 0; })) << "the top list follows the node";
  w.top_field()->setCurrentIndex(w.top_field()->findText("b"));
  EXPECT_TRUE(wait_for([&] { return text(w.inclination_field()) == "0"; }))  // tippe_top: a level plane
      << "the fields show the picked top: " << text(w.inclination_field());
  click(w, "Kill picked");
  EXPECT_TRUE(wait_for([] { return tops() == std::vector<std::string>{"top"}; })) << w.message();
  EXPECT_EQ(w.message(), "Killed top 'b' (1 top left).");
  type(w.spawn_file_field(), "tippe_tap");
  click(w, "Spawn");
  EXPECT_TRUE(starts_with(w.message(), "Nothing was spawned: tippe_tap: no shipped scene has this name"))
      << w.message();
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_panel_widget");
  QApplication app(argc, argv);
  QApplication::setFont(QFont("Sans Serif", 9));  // the offscreen platform's default is 12 pt, X's and rviz's 9 pt
  return RUN_ALL_TESTS();
}
