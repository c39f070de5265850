#include "pqMMVPanelProbe.h"

#include "pqPropertiesPanel.h"
#include "pqPropertyWidget.h"
#include "pqProxyWidget.h"
#include "pqSearchBox.h"
#include "vtkSMProperty.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QLabel>
#include <QMainWindow>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QTextStream>
#include <QTimer>

#include <algorithm>

namespace
{
QMainWindow* MainWindow()
{
  for (QWidget* widget : QApplication::topLevelWidgets())
  {
    if (auto* window = qobject_cast<QMainWindow*>(widget))
    {
      return window;
    }
  }
  return nullptr;
}

// The closest pqPropertyWidget above `widget`, up to (not including) `top`:
// widgets nested in another property widget are that widget's parts.
bool InsidePropertyWidget(QWidget* widget, QWidget* top)
{
  for (QWidget* p = widget->parentWidget(); p && p != top; p = p->parentWidget())
  {
    if (qobject_cast<pqPropertyWidget*>(p))
    {
      return true;
    }
  }
  return false;
}
}

pqMMVPanelProbe::pqMMVPanelProbe(QObject* parent)
  : QObject(parent)
{
}

pqMMVPanelProbe::~pqMMVPanelProbe() = default;

void pqMMVPanelProbe::onStartup()
{
  // The plugin may load before the main window exists.
  QTimer::singleShot(0, this, &pqMMVPanelProbe::installAction);
}

void pqMMVPanelProbe::onShutdown() {}

void pqMMVPanelProbe::installAction()
{
  QMainWindow* window = MainWindow();
  if (!window)
  {
    QTimer::singleShot(200, this, &pqMMVPanelProbe::installAction);
    return;
  }
  auto* action = new QAction(QStringLiteral("Record Properties Panel"), window);
  action->setObjectName(QStringLiteral("mmvPanelProbe"));
  window->addAction(action);
  QObject::connect(action, &QAction::triggered, this, &pqMMVPanelProbe::record);
}

void pqMMVPanelProbe::record()
{
  const QString folder = qEnvironmentVariable("MMV_PANEL_PROBE");
  QMainWindow* window = MainWindow();
  auto* panel = window ? window->findChild<pqPropertiesPanel*>() : nullptr;
  QWidget* display = panel ? panel->findChild<QWidget*>(QStringLiteral("DisplayFrame")) : nullptr;
  auto* proxyWidget = display ? display->findChild<pqProxyWidget*>() : nullptr;
  if (folder.isEmpty() || !proxyWidget)
  {
    qWarning("pqMMVPanelProbe: no MMV_PANEL_PROBE folder or no display panel");
    return;
  }
  // Let pending layout and decorator updates land first.
  QApplication::processEvents();

  auto* searchBox = panel->findChild<pqSearchBox*>();
  const bool advanced = searchBox && searchBox->isAdvancedSearchActive();
  QStringList shown;
  for (pqPropertyWidget* widget : proxyWidget->findChildren<pqPropertyWidget*>())
  {
    // isVisible(): the widget and every ancestor are shown (scrolled-out
    // rows count as shown, as they are one scroll away).
    if (!widget->isVisible() || InsidePropertyWidget(widget, proxyWidget))
    {
      continue;
    }
    vtkSMProperty* property = widget->property();
    shown << QStringLiteral("widget %1 %2 %3")
               .arg(widget->objectName().isEmpty() ? QStringLiteral("-") : widget->objectName(),
                 property && property->GetXMLName() ? property->GetXMLName() : "-",
                 widget->metaObject()->className());
  }
  // The group headers ParaView draws above each group of rows.
  for (QLabel* label : proxyWidget->findChildren<QLabel*>())
  {
    if (label->isVisible() && !InsidePropertyWidget(label, proxyWidget) &&
      !qobject_cast<pqPropertyWidget*>(label->parentWidget()) &&
      label->objectName() != QLatin1String("qt_scrollarea_viewport"))
    {
      QString text = label->text().simplified();
      text.remove(QRegExp(QStringLiteral("<[^>]*>")));
      shown << QStringLiteral("label %1").arg(text);
    }
  }
  std::sort(shown.begin(), shown.end());

  QDir().mkpath(folder);
  const QString image = QStringLiteral("panel-%1-<page>.png").arg(++this->Records);
  // What the screen shows, page by page down the scroll area: pixels read
  // back from the X server, so a widget that paints nothing shows as such.
  auto* scroll = panel->findChild<QScrollArea*>();
  QScrollBar* bar = scroll ? scroll->verticalScrollBar() : nullptr;
  QScreen* screen = QApplication::primaryScreen();
  if (bar && screen)
  {
    const QRect area(panel->mapTo(window, QPoint(0, 0)), panel->size());
    const int step = std::max(1, bar->pageStep() - 40); // pages overlap a little
    int page = 0;
    for (int value = bar->minimum();; value += step)
    {
      bar->setValue(std::min(value, bar->maximum()));
      QApplication::processEvents();
      screen->grabWindow(window->winId(), area.x(), area.y(), area.width(), area.height())
        .save(QDir(folder).filePath(QString(image).replace("<page>", QString::number(++page))));
      if (value >= bar->maximum())
      {
        break;
      }
    }
    bar->setValue(bar->minimum());
  }

  QFile file(QDir(folder).filePath(QStringLiteral("panel.txt")));
  if (!file.open(QIODevice::Append | QIODevice::Text))
  {
    return;
  }
  QTextStream out(&file);
  // The width the rows ask for against the width the dock gives them: more
  // means a horizontal scroll bar.
  out << "record " << this->Records << " advanced " << (advanced ? 1 : 0) << " image " << image
      << " needs_width " << proxyWidget->minimumSizeHint().width() << " viewport_width "
      << (scroll ? scroll->viewport()->width() : 0) << "\n";
  for (const QString& line : shown)
  {
    out << line << "\n";
  }
  out << "end\n";
}
